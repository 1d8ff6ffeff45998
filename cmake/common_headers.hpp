// SPDX-License-Identifier: LGPL-3.0-or-later
// The headers that most of breastsim's C++ files include (directly or through
// the model's headers), precompiled once (CMakeLists.txt, BREASTSIM_PCH) and
// shared by every layer: parsing them is about a third of a file's compile time.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <mpi.h>
#include <petscksp.h>
#include <petscmat.h>
#include <petscvec.h>

#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/Mesh.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
