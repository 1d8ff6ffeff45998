// SPDX-License-Identifier: LGPL-3.0-or-later
// The option structs (src/case/*_options.hpp, term_switches.hpp): defaults,
// --set values reaching their fields, and each struct reading exactly the
// keys it declares.
#include "case_options.hpp"
#include "config.hpp"
#include "output_options.hpp"
#include "solver_options.hpp"
#include "surgery_options.hpp"
#include "term_switches.hpp"
#include "breastsim_registry.hpp"
#include <algorithm>
#include <functional>
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
/// One option struct seen through its keys: the keys it declares and whether
/// two configs give it the same value.
struct OptionStruct
{
  std::string name;
  std::vector<std::string> keys;
  std::function<bool(const Config&, const Config&)> same;
};

std::vector<std::string> key_names(const std::vector<KeyInfo>& keys)
{
  std::vector<std::string> names;
  for (const auto& k : keys)
    names.push_back(k.key);
  return names;
}

template <class X>
std::vector<std::string> declared_keys()
{
  std::vector<KeyInfo> keys;
  X::declare(keys);
  return key_names(keys);
}

template <class X>
std::function<bool(const Config&, const Config&)> same_struct()
{
  return [](const Config& a, const Config& b) { return X::from(a) == X::from(b); };
}

template <class X>
OptionStruct option_struct(const std::string& name)
{
  return {name, declared_keys<X>(), same_struct<X>()};
}

/// NewtonOptions' keys: the solver section's without those of the coarse
/// start, the load steps and the PETSc options.
std::vector<std::string> newton_keys()
{
  std::vector<std::string> others = declared_keys<CoarseStartOptions>();
  const auto load = declared_keys<LoadStepOptions>();
  others.insert(others.end(), load.begin(), load.end());
  others.push_back("solver.petsc_options");
  std::vector<std::string> keys;
  for (const auto& k : declared_keys<SolverOptions>())
    if (std::find(others.begin(), others.end(), k) == others.end())
      keys.push_back(k);
  return keys;
}

std::vector<OptionStruct> option_structs()
{
  return {option_struct<CaseOptions>("CaseOptions"),
          option_struct<HalfCapSpec>("HalfCapSpec"),
          option_struct<SolverOptions>("SolverOptions"),
          {"NewtonOptions", newton_keys(), same_struct<NewtonOptions>()},
          option_struct<CoarseStartOptions>("CoarseStartOptions"),
          option_struct<LoadStepOptions>("LoadStepOptions"),
          option_struct<SurgeryOptions>("SurgeryOptions"),
          option_struct<IncisionSpec>("IncisionSpec"),
          option_struct<OutputOptions>("OutputOptions"),
          option_struct<TermSwitches>("TermSwitches")};
}

/// A value of key k's type that differs from its default.
Value other_value(const KeyInfo& k)
{
  const Value& d = k.default_value;
  switch (k.type)
  {
  case KeyType::number: return std::get<double>(d) + 1.0;
  case KeyType::integer: return std::get<std::int64_t>(d) + 1;
  case KeyType::boolean: return !std::get<bool>(d);
  case KeyType::string:
    for (const auto& choice : k.choices)
      if (choice != std::get<std::string>(d))
        return choice;
    return std::get<std::string>(d) + "_other";
  case KeyType::number_list:
  {
    auto xs = std::get<std::vector<double>>(d);
    xs.push_back(1.5);
    return xs;
  }
  case KeyType::string_list:
  {
    const std::vector<std::string> one{k.choices.empty() ? "other" : k.choices.back()};
    return one != std::get<std::vector<std::string>>(d) ? one : std::vector<std::string>{};
  }
  }
  return d;
}

bool contains(const std::vector<std::string>& keys, const std::string& key)
{
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}
} // namespace

TEST(Options, FromDefaultConfigEqualsTheInitialisers)
{
  const Config c;
  EXPECT_TRUE(CaseOptions::from(c) == CaseOptions{});
  EXPECT_TRUE(HalfCapSpec::from(c) == HalfCapSpec{});
  EXPECT_TRUE(SolverOptions::from(c) == SolverOptions{});
  EXPECT_TRUE(NewtonOptions::from(c) == NewtonOptions{});
  EXPECT_TRUE(CoarseStartOptions::from(c) == CoarseStartOptions{});
  EXPECT_TRUE(LoadStepOptions::from(c) == LoadStepOptions{});
  EXPECT_TRUE(SurgeryOptions::from(c) == SurgeryOptions{});
  EXPECT_TRUE(IncisionSpec::from(c) == IncisionSpec{});
  EXPECT_TRUE(OutputOptions::from(c) == OutputOptions{});
  EXPECT_TRUE(TermSwitches::from(c) == TermSwitches{});
}

TEST(Options, SetValuesReachTheFields)
{
  Config c;
  c.set_text("case.name", "left");
  c.set_text("geometry.order", "2");
  c.set_text("base.fixed", "true");
  c.set_text("gravity.g", "9.5");
  c.set_text("postures.theta_deg", "10,20");
  c.set_text("solver.rtol", "1e-7");
  c.set_text("solver.linear", "amg");
  c.set_text("solver.inexact_newton", "false");
  c.set_text("solver.max_iterations", "7");
  c.set_text("solver.nested_levels", "3");
  c.set_text("solver.min_load_step", "0.01");
  c.set_text("solver.petsc_options", "-ksp_monitor");
  c.set_text("incision.a_deg", "45");
  c.set_text("surgery.max_gap", "0.002");
  c.set_text("solver.max_memory_gb", "3");
  c.set_text("output.vtk", "true");
  const std::string term = generated::terms().front().name;
  c.set("terms." + term, !generated::terms().front().default_on);

  const CaseOptions cs = CaseOptions::from(c);
  EXPECT_EQ(cs.name, "left");
  EXPECT_EQ(cs.geometry.order, 2);
  EXPECT_TRUE(cs.fixed_base);
  EXPECT_EQ(cs.gravity, 9.5);
  EXPECT_EQ(cs.posture_angles_deg, (std::vector<double>{10, 20}));
  const SolverOptions s = SolverOptions::from(c);
  EXPECT_EQ(NewtonOptions::from(c).rtol, 1e-7);
  EXPECT_EQ(s.newton.linear, "amg");
  EXPECT_FALSE(s.newton.inexact);
  EXPECT_EQ(s.newton.max_iterations, 7);
  EXPECT_EQ(s.coarse_start.nested_levels, 3);
  EXPECT_EQ(LoadStepOptions::from(c).min_step, 0.01);
  EXPECT_EQ(s.petsc_options, "-ksp_monitor");
  EXPECT_EQ(SurgeryOptions::from(c).incision.a_deg, 45);
  EXPECT_EQ(SurgeryOptions::from(c).max_gap, 0.002);
  EXPECT_EQ(OutputOptions::from(c).max_memory_gb, 3);
  EXPECT_TRUE(OutputOptions::from(c).vtk);
  EXPECT_EQ(TermSwitches::from(c).is_on(term), !generated::terms().front().default_on);
}

// Every declared key changes the struct when set, and no other key of the
// schema does: the struct reads exactly the keys it declares.
TEST(Options, EachStructReadsExactlyTheKeysItDeclares)
{
  const Config defaults;
  for (const auto& s : option_structs())
  {
    EXPECT_FALSE(s.keys.empty()) << s.name;
    for (const auto& key : s.keys)
      EXPECT_NO_THROW(key_info(key)) << s.name << " declares " << key << ", not in the schema";
    for (const auto& k : schema())
    {
      Config c;
      c.set(k.key, other_value(k));
      if (contains(s.keys, k.key))
        EXPECT_FALSE(s.same(c, defaults)) << s.name << " declares " << k.key << " but does not read it";
      else
        EXPECT_TRUE(s.same(c, defaults)) << s.name << " reads " << k.key << " without declaring it";
    }
  }
}

// The schema: the sections' keys in order (case, solver, surgery, output),
// then the generated physics parameters, then the term switches.
TEST(Options, SchemaIsTheSectionsThenTheGeneratedKeys)
{
  std::vector<std::string> expected;
  for (const auto& section : {declared_keys<CaseOptions>(), declared_keys<SolverOptions>(),
                              declared_keys<SurgeryOptions>(), declared_keys<OutputOptions>()})
    expected.insert(expected.end(), section.begin(), section.end());
  const std::size_t fixed = expected.size();
  for (const auto& p : generated::parameters())
    if (!p.key.empty() && !contains(expected, p.key))
      expected.push_back(p.key);
  const auto terms = declared_keys<TermSwitches>();
  expected.insert(expected.end(), terms.begin(), terms.end());
  EXPECT_EQ(key_names(schema()), expected);
  EXPECT_EQ(terms.size(), generated::terms().size());
  for (std::size_t i = fixed; i < schema().size() - terms.size(); ++i)
    EXPECT_FALSE(schema()[i].ufl_name.empty()) << schema()[i].key << " is no generated parameter";
}

// The defaults are written once, in the structs: the schema's defaults are
// theirs (e.g. the incision's h and d).
TEST(Options, SchemaDefaultsAreTheInitialisers)
{
  const IncisionSpec inc;
  EXPECT_EQ(std::get<double>(key_info("incision.h").default_value), inc.h);
  EXPECT_EQ(std::get<double>(key_info("incision.d").default_value), inc.d);
  EXPECT_EQ(std::get<double>(key_info("solver.rtol").default_value), NewtonOptions{}.rtol);
  EXPECT_EQ(std::get<std::int64_t>(key_info("geometry.order").default_value), HalfCapSpec{}.order);
  EXPECT_EQ(std::get<std::vector<std::string>>(key_info("postures.names").default_value),
            CaseOptions{}.posture_names);
}
