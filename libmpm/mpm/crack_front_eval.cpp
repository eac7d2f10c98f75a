// The crack-front evaluation (crack_front_eval.hpp), compiled once per shape-function style.
#include "libmpm/mpm/crack_front_eval.hpp"

namespace cleave {

template <class SF>
std::vector<crack::FrontRecord> crack_front_records(const Model<3>& m, const crack::TipSettings& ts,
                                                    const FrontAcceleration& accel, detail::FrontParticles* near) {
  return evaluate_crack_fronts<SF>(m, ts, accel, near);
}

template std::vector<crack::FrontRecord> crack_front_records<LinearShape>(const Model<3>&, const crack::TipSettings&,
                                                                          const FrontAcceleration&, detail::FrontParticles*);
template std::vector<crack::FrontRecord> crack_front_records<UGimpShape>(const Model<3>&, const crack::TipSettings&,
                                                                         const FrontAcceleration&, detail::FrontParticles*);

}  // namespace cleave
