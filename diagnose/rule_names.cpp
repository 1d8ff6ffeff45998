#include "rule_names.hpp"

namespace breastsim::diagnosis
{
const NameTable<NoiseFloor>& noise_floor_names()
{
  static const NameTable<NoiseFloor> t = {{"posture", NoiseFloor::posture}, {"local", NoiseFloor::local}};
  return t;
}

const NameTable<EffectMeasure>& effect_measure_names()
{
  static const NameTable<EffectMeasure> t = {{"all", EffectMeasure::all},
                                             {"largest-posture", EffectMeasure::largest_posture}};
  return t;
}

const NameTable<RefinementAllowance>& refinement_allowance_names()
{
  static const NameTable<RefinementAllowance> t = {{"full", RefinementAllowance::full},
                                                   {"scaled", RefinementAllowance::scaled}};
  return t;
}
} // namespace breastsim::diagnosis
