#pragma once
/// \file Per-batch blocks of a block's batched (AoSoA) arrays that many batches hold alike —
/// the material and section constants and the through-thickness points of a shell block with
/// one section —, stored once per distinct block. Read as the plain array was: value i of the
/// array [b][block] is operator[](i), and a block's values stay contiguous, so a pointer to
/// one (&blocks[b * block]) reads the whole block as before.

#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

namespace xpl::elements {

template <class T>
class SharedBlocks {
 public:
  SharedBlocks() = default;
  /// From the plain array `blocks` ([b][block], `block` values per batch; its size a multiple
  /// of `block`). Blocks equal bit for bit are stored once.
  SharedBlocks(const std::vector<T>& blocks, std::size_t block) : m_block(block) {
    const std::size_t n = block > 0 ? blocks.size() / block : 0;
    m_of_batch.resize(n);
    std::unordered_map<std::string, std::uint32_t> seen;
    for (std::size_t b = 0; b < n; ++b) {
      std::string key(reinterpret_cast<const char*>(&blocks[b * block]), block * sizeof(T));
      const auto [it, added] =
          seen.emplace(std::move(key), static_cast<std::uint32_t>(seen.size()));
      if (added)
        m_table.insert(m_table.end(), blocks.begin() + b * block, blocks.begin() + (b + 1) * block);
      m_of_batch[b] = it->second;
    }
  }

  /// Value i of the plain array. A batch's block is contiguous: &(*this)[b · block] + j is
  /// value b · block + j for j < block.
  const T& operator[](std::size_t i) const {
    return m_table[m_of_batch[i / m_block] * m_block + i % m_block];
  }
  /// Number of distinct blocks stored.
  std::size_t distinct() const { return m_block > 0 ? m_table.size() / m_block : 0; }

 private:
  std::size_t m_block = 1;
  std::vector<std::uint32_t> m_of_batch;  ///< [b]: its block in m_table
  std::vector<T> m_table;                 ///< [distinct block][block]
};

}  // namespace xpl::elements
