// The engine's contact models, one list per kind: the spec loader's names (each model's kName is
// the schema's enum value of proto/dem.proto), the material properties it checks, the parameters
// it reads and the force loops the kernel dispatch makes all come from these lists.
//
// Adding a model: its own file (with its force loops instantiated in its .cpp for a normal model),
// its name or parameters in the schema, and a line here.
#pragma once

#include "contact/normal_hertz.hpp"
#include "contact/normal_linear.hpp"
#include "contact/rolling_cdt.hpp"
#include "contact/rolling_epsd.hpp"
#include "contact/rolling_none.hpp"
#include "contact/tangential_coulomb.hpp"

namespace dem {

using NormalModels = ModelList<LinearNormal, HertzNormal>;
// The first that `wanted` the scene is used (Frictionless when no pair has friction).
using TangentialModels = ModelList<CoulombFriction, Frictionless>;
using RollingModels = ModelList<NoRolling, CdtRolling, EpsdRolling>;

}  // namespace dem
