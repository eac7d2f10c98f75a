// Shape functions by scene name ("mpm.shape_function"). A style is a struct of shape_function.hpp;
// it is registered at the bottom of mpm/mpm_step.cpp together with the stepper compiled for it
// (MpmStepper<Dim, Style>): the hot loops are templated on the style, so the choice is made once
// per run, in make_stepper, and never per particle.
#pragma once
#include <memory>
#include <stdexcept>
#include <string>

#include "libmpm/core/registry.hpp"
#include "libmpm/shape/shape_function.hpp"

namespace cleave {

template <int Dim>
class Stepper;
template <int Dim>
struct Model;

struct ShapeFunctionStyle {
  ShapeFunctionKind kind;
  int K;  // nodes per axis in a particle's stencil (stencil_fits)
  std::unique_ptr<Stepper<2>> (*stepper2)(Model<2>&);
  std::unique_ptr<Stepper<3>> (*stepper3)(Model<3>&);
};
using ShapeFunctions = NameTable<ShapeFunctionStyle>;

// The registered style of a kind (std::logic_error when its registrar is missing from the build).
inline const ShapeFunctionStyle& shape_function_style(ShapeFunctionKind kind) {
  const ShapeFunctionStyle* found = nullptr;
  ShapeFunctions::instance().each([&](const std::string&, const ShapeFunctionStyle& s) {
    if (s.kind == kind) found = &s;
  });
  if (!found) throw std::logic_error("no shape function is registered for this ShapeFunctionKind");
  return *found;
}

}  // namespace cleave

// Registers a shape-function style under Style::name; make<Dim, Style>(Model<Dim>&) builds its
// stepper. Used where the stepper template is defined (mpm/mpm_step.cpp).
#define CLEAVE_REGISTER_SHAPE_FUNCTION(Style, make)                                \
  namespace {                                                                    \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_shape_function_) =         \
      ::cleave::ShapeFunctions::instance().add(                                  \
          Style::name,                                                           \
          ::cleave::ShapeFunctionStyle{Style::kind, Style::K, &make<2, Style>,   \
                                       &make<3, Style>});                        \
  }
