// SPDX-License-Identifier: MIT
// Token reader: mirrors token_writer. A small state machine over the grammar of token_format.md §11;
// every rejection names the position and id of the offending token and the rule it breaks.
#include "tokenizer/packing/token_reader.h"

#include <string>

#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/tokenizer.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

enum class State { kWantC, kWantK, kWantO, kWantU0, kWantS, kAfterS, kAfterB };

bool In(int32_t id, int32_t begin, int32_t end) { return id >= begin && id < end; }

const char* ClassName(int32_t id) {
  if (In(id, vocab::kCBegin, vocab::kCEnd)) return "component start C";
  if (In(id, vocab::kUBegin, vocab::kUEnd)) return "layer end U";
  if (In(id, vocab::kEBegin, vocab::kEEnd)) return "component end E";
  if (In(id, vocab::kXBegin, vocab::kXEnd)) return "self-layer extra token X";
  if (In(id, vocab::kSBegin, vocab::kSEnd)) return "self-layer window token S";
  if (In(id, vocab::kBBegin, vocab::kBEnd)) return "between-layer token B";
  if (In(id, vocab::kKBegin, vocab::kKEnd)) return "block token K";
  return "offset token O";
}

// Token positions of one vertex's topology tokens, kept until its layer closes (the
// deferred checks of §11.2/§11.3 need the layer size).
struct VertexPositions {
  int64_t s_pos = 0;
  std::vector<int64_t> x_pos;
  std::vector<int64_t> b_pos;
};

class Reader {
 public:
  explicit Reader(const std::vector<int32_t>& ids) : ids_(ids) {}

  StatusOr<LayeredStream> Run() {
    if (static_cast<int64_t>(ids_.size()) > kMaxReadTokens) {
      return LimitExceeded("token stream of " + std::to_string(ids_.size()) +
                           " ids is longer than the reader's limit of " + std::to_string(kMaxReadTokens));
    }
    if (ids_.empty()) return ParseError("empty token stream: a sequence starts with C (id 0)");
    for (pos_ = 0; pos_ < static_cast<int64_t>(ids_.size()); ++pos_) {
      SILK_RETURN_IF_ERROR(Step(ids_[pos_]));
    }
    if (state_ != State::kWantC) {
      return ParseError("token stream ends inside component " + std::to_string(out_.components.size() - 1) +
                        " (after " + std::to_string(ids_.size()) + " tokens): the last component needs its E");
    }
    return std::move(out_);
  }

 private:
  Status Error(const std::string& why) const {
    return ParseError("token " + std::to_string(pos_) + " (id " + std::to_string(ids_[pos_]) + "): " + why);
  }
  Status ErrorAt(int64_t p, const std::string& why) const {
    return ParseError("token " + std::to_string(p) + " (id " + std::to_string(ids_[p]) + "): " + why);
  }
  StreamComponent& Comp() { return out_.components.back(); }
  StreamLayer& Layer() { return Comp().layers.back(); }
  int32_t LayerIndex() { return static_cast<int32_t>(Comp().layers.size()) - 1; }

  Status Unexpected(int32_t id, const char* wanted) {
    return Error(std::string(ClassName(id)) + " where " + wanted + " is required");
  }

  Status Step(int32_t id) {
    if (id < 0 || id >= vocab::k_format_vocab_size) {
      return Error("not a token id of the format (valid ids are 0.." + std::to_string(vocab::k_format_vocab_size - 1) +
                   ")");
    }
    switch (state_) {
      case State::kWantC:
        if (id != vocab::kCBegin) {
          return Unexpected(id, out_.components.empty() ? "C (a sequence starts with a component)"
                                                        : "C or the end of the sequence (after E)");
        }
        out_.components.emplace_back();
        Comp().layers.emplace_back();
        layer_pos_.clear();
        state_ = State::kWantK;
        return Status::Ok();
      case State::kWantK:
        if (!In(id, vocab::kKBegin, vocab::kKEnd)) return Unexpected(id, "a vertex's block token K");
        if (static_cast<int32_t>(Layer().vertices.size()) >= vocab::k_layer_vertex_limit) {
          return Error("layer " + std::to_string(LayerIndex()) + " would exceed " +
                       std::to_string(vocab::k_layer_vertex_limit) + " vertices");
        }
        pending_block_ = id;
        state_ = State::kWantO;
        return Status::Ok();
      case State::kWantO: {
        if (!In(id, vocab::kOBegin, vocab::kOEnd)) return Unexpected(id, "the offset token O after K");
        StreamVertex v;
        v.pos = VertexOfTokens(pending_block_, id);
        Layer().vertices.push_back(std::move(v));
        layer_pos_.emplace_back();
        state_ = LayerIndex() == 0 ? State::kWantU0 : State::kWantS;
        return Status::Ok();
      }
      case State::kWantU0:
        if (id != vocab::kUBegin) return Unexpected(id, "U (layer 0 holds only the root vertex)");
        return OpenLayer();
      case State::kWantS:
        if (In(id, vocab::kBBegin, vocab::kBEnd)) return Error("between-layer token before the vertex's S token");
        if (In(id, vocab::kXBegin, vocab::kXEnd)) return Error("self-layer extra token before the vertex's S token");
        if (!In(id, vocab::kSBegin, vocab::kSEnd)) return Unexpected(id, "the vertex's window token S");
        Layer().vertices.back().window = id - vocab::kSBegin;
        layer_pos_.back().s_pos = pos_;
        state_ = State::kAfterS;
        return Status::Ok();
      case State::kAfterS:
        if (In(id, vocab::kXBegin, vocab::kXEnd)) return ReadExtra(id);
        if (In(id, vocab::kBBegin, vocab::kBEnd)) return ReadBetween(id);
        if (In(id, vocab::kSBegin, vocab::kSEnd)) return Error("second S token for one vertex");
        return Unexpected(id, "an X or B token (every vertex of layer >= 1 has at least one B token)");
      case State::kAfterB:
        if (In(id, vocab::kBBegin, vocab::kBEnd)) return ReadBetween(id);
        if (In(id, vocab::kKBegin, vocab::kKEnd)) {
          state_ = State::kWantK;
          return Step(id);
        }
        if (id == vocab::kUBegin) {
          SILK_RETURN_IF_ERROR(CloseLayer());
          return OpenLayer();
        }
        if (id == vocab::kEBegin) {
          SILK_RETURN_IF_ERROR(CloseLayer());
          state_ = State::kWantC;
          return Status::Ok();
        }
        if (In(id, vocab::kXBegin, vocab::kXEnd)) return Error("self-layer extra token after the vertex's B tokens");
        return Unexpected(id, "a B token, the next vertex's K, U or E");
    }
    return InternalError("token reader in an unknown state");
  }

  Status OpenLayer() {
    if (static_cast<int32_t>(Comp().layers.size()) >= vocab::k_layer_count_limit) {
      return Error("component " + std::to_string(out_.components.size() - 1) + " would get more than " +
                   std::to_string(vocab::k_layer_count_limit) + " layers");
    }
    prev_size_ = static_cast<int32_t>(Layer().vertices.size());
    Comp().layers.emplace_back();
    layer_pos_.clear();
    state_ = State::kWantK;
    return Status::Ok();
  }

  Status ReadExtra(int32_t id) {
    const int32_t e = id - vocab::kXBegin;
    auto& v = Layer().vertices.back();
    if (e < vocab::k_self_window) {
      return Error("self-layer extra value " + std::to_string(e) + " is below " + std::to_string(vocab::k_self_window) +
                   " (distances 1..8 belong to the S window)");
    }
    if (!v.extras.empty() && e <= v.extras.back()) {
      return Error("self-layer extra values must increase within a vertex (" + std::to_string(e) + " after " +
                   std::to_string(v.extras.back()) + ")");
    }
    v.extras.push_back(e);
    layer_pos_.back().x_pos.push_back(pos_);
    return Status::Ok();
  }

  Status ReadBetween(int32_t id) {
    const int32_t r = id - vocab::kBBegin;
    BetweenToken t{r / kBetweenCases, r % kBetweenCases};
    auto& v = Layer().vertices.back();
    if (LayerIndex() == 1) {
      if (!v.between.empty()) return Error("a layer-1 vertex has exactly one B token (460)");
      if (id != vocab::kBBegin + 1)
        return Error("a layer-1 vertex's B token must be 460 (its only neighbour is the root)");
    }
    if (t.start + BetweenCaseLastOne(t.kase) > prev_size_ - 1) {
      return Error("between-layer segment (start " + std::to_string(t.start) + ", case " + std::to_string(t.kase) +
                   ") reaches past the previous layer of " + std::to_string(prev_size_) + " vertices");
    }
    if (!v.between.empty()) {
      const BetweenToken& p = v.between.back();
      const int32_t min_start = BetweenNextMinStart(p.start, p.kase);
      if (t.start < min_start) {
        return Error("between-layer token starts at column " + std::to_string(t.start) + ", but after (start " +
                     std::to_string(p.start) + ", case " + std::to_string(p.kase) +
                     ") the row continues at column >= " + std::to_string(min_start));
      }
    }
    v.between.push_back(t);
    layer_pos_.back().b_pos.push_back(pos_);
    state_ = State::kAfterB;
    return Status::Ok();
  }

  // Deferred conditions of §11.2 / §11.4 once the layer size N is known.
  Status CloseLayer() {
    const auto& vs = Layer().vertices;
    const int32_t n = static_cast<int32_t>(vs.size());
    for (int32_t i = 0; i < n; ++i) {
      if (n <= vocab::k_self_window && (vs[i].window >> (n - 1)) != 0) {
        return ErrorAt(layer_pos_[i].s_pos, "window bits point past the end of a layer of " + std::to_string(n) +
                                                " vertices (layer closed at token " + std::to_string(pos_) + ")");
      }
      for (size_t k = 0; k < vs[i].extras.size(); ++k) {
        if (vs[i].extras[k] > n - 10) {
          return ErrorAt(layer_pos_[i].x_pos[k], "self-layer extra value " + std::to_string(vs[i].extras[k]) +
                                                     " is out of range for a layer of " + std::to_string(n) +
                                                     " vertices (max N-10 = " + std::to_string(n - 10) +
                                                     "; layer closed at token " + std::to_string(pos_) + ")");
        }
      }
    }
    if (LayerIndex() == 1 && n < 2) {
      return Error("layer 1 has " + std::to_string(n) + " vertex; the root has at least 2 neighbours");
    }
    return Status::Ok();
  }

  const std::vector<int32_t>& ids_;
  LayeredStream out_;
  State state_ = State::kWantC;
  int64_t pos_ = 0;
  int32_t pending_block_ = 0;
  int32_t prev_size_ = 0;
  std::vector<VertexPositions> layer_pos_;
};

}  // namespace

StatusOr<LayeredStream> ReadTokens(const std::vector<int32_t>& ids) { return Reader(ids).Run(); }

StatusOr<LayeredStream> ReadTokenStream(const std::vector<int32_t>& ids) { return ReadTokens(ids); }

}  // namespace silk
