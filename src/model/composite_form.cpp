// SPDX-License-Identifier: LGPL-3.0-or-later
#include "composite_form.hpp"
#include <dolfinx/fem/FiniteElement.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <algorithm>
#include <functional>
#include <stdexcept>

namespace breastsim
{
using namespace dolfinx;
using T = PetscScalar;
using Kernel = std::function<void(T*, const T*, const T*, const double*, const int*,
                                  const std::uint8_t*)>;

namespace
{
/// Index of `item` in `all` (appended if absent).
template <typename P>
std::size_t index_in(std::vector<P>& all, const P& item)
{
  auto it = std::find(all.begin(), all.end(), item);
  if (it != all.end())
    return static_cast<std::size_t>(it - all.begin());
  all.push_back(item);
  return all.size() - 1;
}

/// Start of every coefficient's dofs in a packed entity array, and the end.
std::vector<int> coefficient_starts(const std::vector<std::shared_ptr<const fem::Function<T>>>& w)
{
  std::vector<int> s{0};
  for (const auto& f : w)
    s.push_back(s.back() + f->function_space()->element()->space_dimension());
  return s;
}

std::vector<int> constant_starts(const std::vector<std::shared_ptr<const fem::Constant<T>>>& c)
{
  std::vector<int> s{0};
  for (const auto& k : c)
    s.push_back(s.back() + static_cast<int>(k->value.size()));
  return s;
}

/// Positions in the composite's packed array of each entry of a term's
/// packed array (term item i = composite item map[i]); empty when the term's
/// array is a prefix of the composite's (no gather needed).
std::vector<int> gather_positions(const std::vector<int>& term_starts,
                                  const std::vector<int>& all_starts,
                                  const std::vector<std::size_t>& map)
{
  std::vector<int> pos;
  bool prefix = true;
  for (std::size_t i = 0; i < map.size(); ++i)
    for (int k = 0; k < term_starts[i + 1] - term_starts[i]; ++k)
    {
      pos.push_back(all_starts[map[i]] + k);
      prefix = prefix && pos.back() == static_cast<int>(pos.size()) - 1;
    }
  return prefix ? std::vector<int>{} : pos;
}

/// One term's kernel for one integral, with its gathers and switch.
struct TermKernel
{
  Kernel kernel;
  std::shared_ptr<const fem::Constant<T>> on;
  std::vector<int> w_pos, c_pos; ///< gather positions (empty: pass through)
  std::vector<T> w, c;           ///< gather buffers

  const T* gather(const T* all, const std::vector<int>& pos, std::vector<T>& buf)
  {
    if (pos.empty())
      return all;
    for (std::size_t i = 0; i < pos.size(); ++i)
      buf[i] = all[pos[i]];
    return buf.data();
  }
};
} // namespace

std::shared_ptr<fem::Form<T>> compose_forms(const std::vector<SwitchedForm>& terms,
                                            const mesh::MeshTags<std::int32_t>* facet_tags)
{
  if (terms.empty())
    throw std::logic_error("compose_forms: no terms");
  const auto& first = *terms.front().form;
  std::vector<std::shared_ptr<const fem::Function<T>>> coefficients;
  std::vector<std::shared_ptr<const fem::Constant<T>>> constants;
  struct TermMaps { std::vector<std::size_t> w, c; };
  std::vector<TermMaps> maps;
  bool permutations = false;
  for (const auto& t : terms)
  {
    if (t.form->function_spaces() != first.function_spaces() || t.form->mesh() != first.mesh())
      throw std::logic_error("compose_forms: the terms differ in rank, spaces or mesh");
    TermMaps m;
    for (const auto& w : t.form->coefficients())
      m.w.push_back(index_in(coefficients, w));
    for (const auto& c : t.form->constants())
      m.c.push_back(index_in(constants, c));
    maps.push_back(std::move(m));
    permutations = permutations || t.form->needs_facet_permutations();
  }
  const auto w_all = coefficient_starts(coefficients), c_all = constant_starts(constants);

  using Integrals = std::vector<std::pair<int, Kernel>>;
  std::map<fem::IntegralType, std::pair<Integrals, const mesh::MeshTags<int>*>> integrals;
  for (auto type : {fem::IntegralType::cell, fem::IntegralType::exterior_facet,
                    fem::IntegralType::interior_facet})
  {
    std::map<int, std::vector<TermKernel>> by_id;
    for (std::size_t k = 0; k < terms.size(); ++k)
    {
      const auto& f = *terms[k].form;
      for (int id : f.integral_ids(type))
      {
        if (type == fem::IntegralType::cell && id != -1)
          throw std::logic_error("compose_forms: cell integrals over subdomains are not supported");
        TermKernel tk{f.kernel(type, id), terms[k].on,
                      gather_positions(coefficient_starts(f.coefficients()), w_all, maps[k].w),
                      gather_positions(constant_starts(f.constants()), c_all, maps[k].c), {}, {}};
        tk.w.resize(tk.w_pos.size());
        tk.c.resize(tk.c_pos.size());
        by_id[id].push_back(std::move(tk));
      }
    }
    Integrals list;
    for (auto& [id, kernels] : by_id)
      list.emplace_back(id, [ks = std::move(kernels)](T* A, const T* w, const T* c, const double* x,
                                                      const int* entity, const std::uint8_t* perm) mutable
                        {
                          for (auto& k : ks)
                            if (k.on->value[0] != 0.0)
                              k.kernel(A, k.gather(w, k.w_pos, k.w), k.gather(c, k.c_pos, k.c), x,
                                       entity, perm);
                        });
    if (!list.empty())
      integrals[type] = {std::move(list),
                         type == fem::IntegralType::exterior_facet ? facet_tags : nullptr};
  }
  return std::make_shared<fem::Form<T>>(first.function_spaces(), integrals, coefficients, constants,
                                        permutations, first.mesh());
}
} // namespace breastsim
