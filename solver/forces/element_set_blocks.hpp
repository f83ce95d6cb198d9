#pragma once
/// \file The block loops of ElementSet (element_set.hpp), shared by its sources: private to
/// solver/element_set*.cpp.

#include <tuple>
#include <utility>

#include "solver/forces/element_set.hpp"

namespace xpl {

template <class F>
void ElementSet::for_each_block(F&& f) const {
  std::apply([&](const auto&... block) { ((block ? f(*block) : void()), ...); }, m_blocks);
}

template <class F>
void ElementSet::for_each_block(F&& f) {
  std::apply([&](auto&... block) { ((block ? f(*block) : void()), ...); }, m_blocks);
}

template <std::size_t... I, class F>
void ElementSet::for_each_block(std::index_sequence<I...>, F&& f) {
  ((std::get<I>(m_blocks) ? f(*std::get<I>(m_blocks)) : void()), ...);
}

template <class F>
void ElementSet::for_each_whole_block(F&& f) const {
  if (m_run == nullptr) {
    for_each_block(f);
    return;
  }
  std::apply([&](const auto&... block) { ((block ? f(*block) : void()), ...); }, m_whole);
}

}  // namespace xpl
