#pragma once
// Everything of component coulomb::core (docs/embedding.md): the World, its descriptions, events
// and hooks (coulomb/world.hpp) and scene queries (coulomb/queries.hpp). The optional components
// have their own headers: coulomb/meshes.hpp, coulomb/urdf.hpp, coulomb/io.hpp.
#include <coulomb/queries.hpp>
#include <coulomb/world.hpp>
