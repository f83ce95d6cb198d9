#pragma once
/// \file The element kinds of the solver (elements/element_kind.hpp) and how the model's
/// elements map onto them: which element types a kind takes and the Properties of an element
/// (material, section, section controls), the one place that reads the model for a kind. The
/// element set (element_set.*), *FIXED MASS SCALING (solver/increment/mass_scaling.*) and gravity
/// (solver/loads/gravity_loads.*) fold over ElementKinds; a new kind is a folder in elements/, one
/// entry in ElementKinds and a KindBinding here (docs/dev/extending.md).

#include <tuple>
#include <type_traits>
#include <utility>

#include "common/types.hpp"
#include "elements/element_kind.hpp"
#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/shell/shell4r.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// The kinds, in the order their masses are lumped and their totals summed (a sum in another
/// order differs in the last bits).
using ElementKinds = std::tuple<elements::Hex8rBlock, elements::Hex8Block, elements::Shell4rBlock>;
/// The order of the force pass (ElementKinds indices): nodes shared by several kinds sum
/// their forces C3D8R, S4R, C3D8 (also the order of the partition's node marking).
using ForcePassOrder = std::index_sequence<0, 2, 1>;

/// The model side of kind K: specialised for each kind of ElementKinds.
template <class K>
struct KindBinding;

template <>
struct KindBinding<elements::Hex8rBlock> {
  static bool takes(ElementType type) { return type == ElementType::C3D8R; }
  /// `mass_factor`: the element's *FIXED MASS SCALING factor (1: none), on the density.
  static elements::HexMaterial properties(const Model& model, Index e, Real mass_factor);
};

template <>
struct KindBinding<elements::Hex8Block> {
  static bool takes(ElementType type) { return type == ElementType::C3D8; }
  static elements::HexMaterial properties(const Model& model, Index e, Real mass_factor) {
    return KindBinding<elements::Hex8rBlock>::properties(model, e, mass_factor);
  }
};

template <>
struct KindBinding<elements::Shell4rBlock> {
  static bool takes(ElementType type) { return type == ElementType::S4R; }
  static elements::ShellProperties properties(const Model& model, Index e, Real mass_factor);
};

static_assert(
    []<std::size_t... I>(std::index_sequence<I...>) {
      return (elements::ElementKind<std::tuple_element_t<I, ElementKinds>> && ...);
    }(std::make_index_sequence<std::tuple_size_v<ElementKinds>>{}),
    "every kind of ElementKinds satisfies elements::ElementKind");

/// Calls `f(std::type_identity<K>{})` for the kind K that takes elements of `type` and returns
/// what it returns.
template <class F>
decltype(auto) with_element_kind(ElementType type, F&& f) {
  using R = decltype(f(std::type_identity<std::tuple_element_t<0, ElementKinds>>{}));
  return [&]<std::size_t... I>(std::index_sequence<I...>)->R {
    R result{};
    (void)((KindBinding<std::tuple_element_t<I, ElementKinds>>::takes(type)
                ? (result = f(std::type_identity<std::tuple_element_t<I, ElementKinds>>{}), true)
                : false) ||
           ...);
    return result;
  }
  (std::make_index_sequence<std::tuple_size_v<ElementKinds>>{});
}

/// Lumped mass share (kg) of each node of element e (any element, rigid ones too) in the
/// configuration `reference` (n_nodes × 3, m): the kind's node_mass() with the element's
/// unscaled properties.
Real element_node_mass(const Model& model, Index e, const NodalVectors& reference);

/// Stable increment estimate of element e at rest in the configuration `reference`
/// (n_nodes × 3), s, with the linear bulk viscosity `bulk_linear`: the kind's
/// stable_increment() with the element's unscaled properties.
Real element_stable_increment(const Model& model, Index e, const NodalVectors& reference,
                              Real bulk_linear);

}  // namespace xpl
