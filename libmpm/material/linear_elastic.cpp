// The linear elastic material registers itself under the scene name "linear_elastic"; the class is
// in the header so that the stress pass can call it without a virtual call.
#include "libmpm/material/linear_elastic.hpp"

CLEAVE_REGISTER_MATERIAL("linear_elastic", cleave::LinearElastic)
