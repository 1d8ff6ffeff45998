// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The C++ view of the UFL model (forms/): parameters with their case keys,
// units, defaults and ranges; the energy terms and their default switches;
// the boundary tags; the partner fields; the diagnosis candidates and the
// --fit names the terms declare; the compiled forms. The tables are
// generated from forms/ by forms/gen_registry.py into breastsim_registry.cpp;
// this header does not change when a term is edited or added, so only that
// file and the term's own kernels are recompiled.
#include <string>
#include <utility>
#include <vector>
#include <ufcx.h>

namespace breastsim::generated
{
struct ParamInfo
{
  std::string name; // UFL Constant name
  std::string key;  // case-file key (empty: set by the program)
  std::string unit;
  std::string term;
  std::vector<double> default_value;
  double lo, hi;
  bool lo_open;
  std::string doc;
};

struct TermInfo
{
  std::string name;
  bool default_on;
};

struct TagInfo
{
  std::string name;
  int value;
};

/// A partner field (forms/model.py): Coefficient `coefficient` of term
/// `term` holds w = P u, u at g(X) = G X + t for the nodes X of face_a
/// (G, t: the Constants map_matrix, map_shift); forms partner_*_<term>.
struct PartnerInfo
{
  std::string term, coefficient, face_a, face_b, map_matrix, map_shift;
};

/// How a candidate's q sets a case key (forms/common.py candidate()):
/// key = q, key = 1/q, or key keeps its ratio to the first key set.
enum class CandidateRule
{
  value,
  inverse,
  keep_ratio
};

struct CandidateSetting
{
  std::string key;
  CandidateRule rule;
};

/// A diagnosis candidate (a term's CANDIDATE in forms/): the term switched
/// on with one scalar q >= 0; q = 0 reproduces the model without it.
struct CandidateInfo
{
  std::string term;      // the term's name = the candidate's name
  std::string parameter; // reported name of q, e.g. "ligament.k"
  std::string unit;
  std::string physics;   // what it stands for, in plain words
  double typical;        // size of a clearly visible effect [unit]
  std::vector<CandidateSetting> sets;               // the case keys q sets, in order
  std::vector<std::pair<std::string, bool>> flags;  // case flags set with the term on
  std::string family;    // the physics it names (its own name unless another form shares it)
  std::string extends;   // the candidate it refines (applies only where that term is on), or ""
  bool in_default_library; // tested by a diagnosis without --candidates
};

/// What a fitted parameter is: sets its search bounds and the
/// identifiability rule (a density never with a stiffness).
enum class FitRole
{
  stiffness,
  density,
  shape
};

/// A --fit name (a term's FIT, or the neutral shape's GEOMETRY_FIT in forms/common.py).
struct FitAliasInfo
{
  std::string alias; // e.g. "mu"
  std::string key;   // case key, e.g. "tissue.mu"
  std::string term;  // declaring term ("": the neutral shape)
  FitRole role;
};

const std::vector<ParamInfo>& parameters();
const std::vector<TermInfo>& terms();
const std::vector<TagInfo>& tags();
const std::vector<PartnerInfo>& partners();
const std::vector<CandidateInfo>& candidates();
const std::vector<FitAliasInfo>& fit_aliases();
/// Value of the boundary tag `name`; throws std::logic_error if unknown.
int tag(const std::string& name);

/// Compiled form `name` of element degree `degree`, nullptr if there is
/// none: per term energy_<t>, residual_<t>, jacobian_<t> (and
/// partner_residual_<t>, partner_jacobian_uw_<t>, partner_jacobian_ww_<t>
/// for a term with a partner field); volume and area_<tag>.
ufcx_form* form(const std::string& name, int degree);
/// det F at the inversion check points (forms/geometry_forms.py).
ufcx_expression* detF_expression(int degree);
/// Factory of the displacement space ('u') of the compiled model.
using FunctionSpaceFactory = ufcx_function_space* (*)(const char*);
FunctionSpaceFactory function_space(int degree);
/// Element degrees compiled into this build.
std::vector<int> degrees();
} // namespace breastsim::generated
