// SPDX-License-Identifier: LGPL-3.0-or-later
#include "field_term_writer.hpp"
#include <fmt/format.h>
#include <sstream>

namespace breastsim::diagnosis
{
namespace
{
/// Shortest text that reads back as the same double.
std::string exact(double x) { return fmt::format("{}", x); }

/// `text` broken into lines of at most `width` characters at spaces.
std::string wrapped(const std::string& text, std::size_t width)
{
  std::string out, line, word;
  std::istringstream words(text);
  while (words >> word)
  {
    if (!line.empty() && line.size() + 1 + word.size() > width)
    {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

std::string python_list(const std::vector<double>& v)
{
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + exact(v[i]);
  return s + "]";
}
} // namespace

std::string field_term_source(const FieldDiscovery& f, const std::string& name, const std::string& source)
{
  std::string centres = "[";
  for (std::size_t k = 0; k < f.basis.centres.size(); ++k)
    centres += fmt::format("{}({}, {}, {})", k ? ",\n           " : "", exact(f.basis.centres[k][0]),
                           exact(f.basis.centres[k][1]), exact(f.basis.centres[k][2]));
  centres += "]";
  const std::string q = "q_" + name;
  return fmt::format(
      R"PY(# SPDX-License-Identifier: LGPL-3.0-or-later
"""{name}: a stiffness field found by `breastsim diagnose` on {source}:
{words}

    E = int_B q (exp(s(X)) - 1) W(F; mu, lambda) dV,
    s(X) = sum_k a_k exp(-|X - c_k|^2 / (2 w^2)),

W the tissue's density (eq. 5): with the tissue term the tissue is
1 + q (exp(s(X)) - 1) times as stiff at X; q = 1 is the field as
discovered, q = 0 the model without it. To use it: copy this file into
forms/ and add "{name}" to forms/registry.py.
"""
from common import Constant, X, candidate, domain, dx, F, J, neo_hooke, param
from tissue import mu, lmbda
from ufl import as_vector, dot, exp

NAME = "{name}"
DEFAULT_ON = False
{q} = Constant(domain)

PARAMETERS = {{
    "{q}": param("{name}.strength", "1", 1.0, 0.0, 10.0,
                 "strength q of the discovered stiffness field (1: as discovered, 0: none)"),
}}
CANDIDATE = candidate("{name}.strength", "1", 1.0, "{resembles_q}",
                      sets={{"{q}": "q"}}, default=False)

AMPLITUDES = {amplitudes}
CENTRES = {centres}
WIDTH = {width}


def _basis(c):
    d = X - as_vector(c)
    return exp(-dot(d, d) / (2 * WIDTH ** 2))


s_field = sum(a * _basis(c) for a, c in zip(AMPLITUDES, CENTRES))
ENERGY = {q} * (exp(s_field) - 1) * neo_hooke(F, J, mu, lmbda, 3) * dx
)PY",
      fmt::arg("name", name), fmt::arg("source", source), fmt::arg("words", wrapped(f.summary.words + ".", 76)),
      fmt::arg("q", q), fmt::arg("amplitudes", python_list(f.amplitudes)),
      fmt::arg("centres", centres), fmt::arg("width", exact(f.basis.width)),
      fmt::arg("resembles_q", "the discovered stiffness field: " + f.summary.where));
}
} // namespace breastsim::diagnosis
