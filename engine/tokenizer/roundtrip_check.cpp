// SPDX-License-Identifier: MIT
// Round-trip comparison by grid coordinates: faces are put in a canonical rotation (smallest
// corner first) so equal windings compare equal.
#include "tokenizer/roundtrip_check.h"

#include <algorithm>
#include <tuple>

namespace silk {
namespace {

using Key = std::array<int32_t, 9>;

Key Canonical(const std::array<QVec, 3>& f) {
  auto lt = [](const QVec& a, const QVec& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  int s = 0;
  for (int k = 1; k < 3; ++k)
    if (lt(f[k], f[s])) s = k;
  Key key{};
  for (int k = 0; k < 3; ++k) {
    const QVec& q = f[(s + k) % 3];
    key[k * 3] = q.x;
    key[k * 3 + 1] = q.y;
    key[k * 3 + 2] = q.z;
  }
  return key;
}

Key Reversed(const std::array<QVec, 3>& f) { return Canonical({f[0], f[2], f[1]}); }

bool Contains(const std::vector<Key>& sorted, const Key& k) {
  return std::binary_search(sorted.begin(), sorted.end(), k);
}

}  // namespace

RoundTripReport CompareRoundTrip(const EncodeResult& enc, const TokenizerDecodedMesh& dec) {
  RoundTripReport r;
  std::vector<Key> decoded, processed, unencodable;
  for (const auto& f : dec.faces)
    decoded.push_back(Canonical({dec.positions[static_cast<size_t>(f[0])], dec.positions[static_cast<size_t>(f[1])],
                                 dec.positions[static_cast<size_t>(f[2])]}));
  for (const auto& f : enc.processed_faces) processed.push_back(Canonical(f));
  for (const auto& f : enc.unencodable_faces) unencodable.push_back(Canonical(f));
  std::sort(decoded.begin(), decoded.end());
  std::sort(processed.begin(), processed.end());
  std::sort(unencodable.begin(), unencodable.end());
  r.processed_faces = static_cast<int64_t>(processed.size());
  for (const auto& f : enc.processed_faces) {
    const Key k = Canonical(f);
    if (Contains(unencodable, k)) continue;
    ++r.representable_faces;
    if (Contains(decoded, k))
      ++r.recovered;
    else if (Contains(decoded, Reversed(f)))
      ++r.reversed;
    else
      ++r.missing;
  }
  std::vector<Key> processed_unoriented;
  for (const auto& f : enc.processed_faces) {
    processed_unoriented.push_back(Canonical(f));
    processed_unoriented.push_back(Reversed(f));
  }
  std::sort(processed_unoriented.begin(), processed_unoriented.end());
  for (const Key& k : decoded) {
    if (Contains(processed_unoriented, k)) {
      if (Contains(unencodable, k)) ++r.extra_unencodable;
      continue;
    }
    ++r.extra;
  }
  return r;
}

}  // namespace silk
