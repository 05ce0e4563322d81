// SPDX-License-Identifier: MIT
// silk.hpp — thin header-only C++ layer over silk.h: RAII handles and exceptions on the
// C++ side only (the C boundary itself never throws).
#pragma once
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "silk/silk.h"

namespace silk_cpp {

class Error : public std::runtime_error {
 public:
  Error(silk_status s, const std::string& msg) : std::runtime_error(msg), status_(s), message_(msg) {}
  // From Check: what() is "<status name>: <message>", message() the library's text alone.
  Error(silk_status s, const std::string& what, const std::string& message)
      : std::runtime_error(what), status_(s), message_(message) {}
  silk_status status() const { return status_; }
  const std::string& message() const { return message_; }

 private:
  silk_status status_;
  std::string message_;
};

inline void Check(silk_status s) {
  if (s != SILK_OK) {
    const std::string message = silk_last_error();
    throw Error(s, std::string(silk_status_name(s)) + ": " + message, message);
  }
}

// A struct the library fills, ready for the call: zeroed, struct_size set (silk.h, "Struct growth").
template <typename T>
T Sized() {
  T t{};
  t.struct_size = static_cast<uint32_t>(sizeof(T));
  return t;
}

// silk.h's size-query rule: copy(out, capacity, out_count) asked for the count, then called.
template <typename T, typename Copy>
std::vector<T> CopyAll(Copy copy) {
  size_t n = 0;
  Check(copy(static_cast<T*>(nullptr), 0, &n));
  std::vector<T> v(n);
  if (n) Check(copy(v.data(), v.size(), &n));
  return v;
}
// The number of elements a copy function would copy (its size query).
template <typename T, typename Copy>
size_t CountOf(Copy copy) {
  size_t n = 0;
  Check(copy(static_cast<T*>(nullptr), 0, &n));
  return n;
}

inline silk_vocab_info Vocab() {
  silk_vocab_info v = Sized<silk_vocab_info>();
  Check(silk_vocab_get_info(&v));
  return v;
}

// Enum names (silk.h 1.4): every name of an enum, counting up from its first value until the
// library says "unknown" (an option's accepted values), and the value of a name.
inline std::vector<std::string> EnumNames(const char* (*name)(int32_t), int32_t first) {
  std::vector<std::string> names;
  for (int32_t v = first; std::string(name(v)) != "unknown"; ++v) names.emplace_back(name(v));
  return names;
}
inline int32_t EnumValue(silk_status (*from_name)(const char*, int32_t*), const std::string& name) {
  int32_t value = 0;
  Check(from_name(name.c_str(), &value));
  return value;
}

// Files (silk.h "files"): an output path checked before long work, the atomic writer, the
// regular-file reader.
inline void CheckOutputPath(const std::string& path) { Check(silk_file_check_output(path.c_str())); }
inline void WriteFile(const std::string& path, const std::string& bytes) {
  Check(silk_file_write(path.c_str(), bytes.data(), bytes.size()));
}
inline std::string ReadFile(const std::string& path, uint64_t max_bytes) {
  const std::vector<char> v =
      CopyAll<char>([&](char* o, size_t c, size_t* n) { return silk_file_read(path.c_str(), max_bytes, o, c, n); });
  return std::string(v.begin(), v.end());
}

struct ReportDeleter {
  void operator()(silk_report* r) const { silk_report_destroy(r); }
};
// Takes ownership of a silk_report and returns its JSON text.
inline std::string TakeReport(silk_report* r) {
  std::unique_ptr<silk_report, ReportDeleter> owned(r);
  return r ? std::string(silk_report_json(r)) : std::string();
}

struct MeshDeleter {
  void operator()(silk_mesh* m) const { silk_mesh_destroy(m); }
};
struct TokensDeleter {
  void operator()(silk_tokens* t) const { silk_tokens_destroy(t); }
};

class Tokens {
 public:
  explicit Tokens(silk_tokens* t) : h_(t) {}
  static Tokens FromIds(const std::vector<int32_t>& ids) {
    silk_tokens* t = nullptr;
    Check(silk_tokens_create(ids.data(), ids.size(), &t));
    return Tokens(t);
  }
  static Tokens Load(const std::string& path) {
    silk_tokens* t = nullptr;
    Check(silk_tokens_load(path.c_str(), &t));
    return Tokens(t);
  }
  std::vector<int32_t> ids() const {
    return CopyAll<int32_t>([&](int32_t* o, size_t c, size_t* n) { return silk_tokens_copy(h_.get(), o, c, n); });
  }
  void Save(const std::string& path) const { Check(silk_tokens_save(h_.get(), path.c_str())); }
  size_t size() const {
    return CountOf<int32_t>([&](int32_t* o, size_t c, size_t* n) { return silk_tokens_copy(h_.get(), o, c, n); });
  }
  // The grammar's verdict (a rejection is a result, not an exception).
  silk_check_result GrammarCheck(const silk_check_params& p = silk_check_default_params()) const {
    silk_check_result r = Sized<silk_check_result>();
    silk_cpp::Check(silk_tokens_check(h_.get(), &p, &r));
    return r;
  }
  const silk_tokens* get() const { return h_.get(); }

 private:
  std::unique_ptr<silk_tokens, TokensDeleter> h_;
};

class Mesh {
 public:
  explicit Mesh(silk_mesh* m) : h_(m) {}
  static Mesh FromArrays(const std::vector<double>& xyz, const std::vector<int32_t>& tris) {
    silk_mesh* m = nullptr;
    Check(silk_mesh_create(xyz.data(), xyz.size() / 3, tris.data(), tris.size() / 3, &m));
    return Mesh(m);
  }
  static Mesh Load(const std::string& path, const silk_load_params& p = silk_load_default_params()) {
    silk_mesh* m = nullptr;
    Check(silk_mesh_load(path.c_str(), &p, &m));
    return Mesh(m);
  }
  void Save(const std::string& path, const silk_save_params& p = silk_save_default_params()) const {
    Check(silk_mesh_save(h_.get(), path.c_str(), &p));
  }
  size_t vertex_count() const {
    return CountOf<double>(
               [&](double* o, size_t c, size_t* n) { return silk_mesh_copy_positions(h_.get(), o, c, n); }) /
           3;
  }
  size_t triangle_count() const {
    return CountOf<int32_t>(
               [&](int32_t* o, size_t c, size_t* n) { return silk_mesh_copy_triangles(h_.get(), o, c, n); }) /
           3;
  }
  bool is_point_cloud() const { return silk_mesh_has_normals(h_.get()) && triangle_count() == 0; }
  std::vector<double> positions() const {
    return CopyAll<double>([&](double* o, size_t c, size_t* n) { return silk_mesh_copy_positions(h_.get(), o, c, n); });
  }
  std::vector<int32_t> triangles() const {
    return CopyAll<int32_t>(
        [&](int32_t* o, size_t c, size_t* n) { return silk_mesh_copy_triangles(h_.get(), o, c, n); });
  }
  std::vector<int32_t> triangle_components() const {
    return CopyAll<int32_t>(
        [&](int32_t* o, size_t c, size_t* n) { return silk_mesh_copy_triangle_components(h_.get(), o, c, n); });
  }
  std::vector<double> normals() const {
    return CopyAll<double>([&](double* o, size_t c, size_t* n) { return silk_mesh_copy_normals(h_.get(), o, c, n); });
  }
  Tokens Encode(const silk_encode_params& p = silk_encode_default_params(), silk_encode_stats* stats = nullptr) const {
    silk_tokens* t = nullptr;
    Check(silk_mesh_encode(h_.get(), &p, &t, stats));
    return Tokens(t);
  }
  static Mesh Decode(const Tokens& t, const silk_decode_params& p = silk_decode_default_params(),
                     silk_decode_stats* stats = nullptr) {
    silk_mesh* m = nullptr;
    Check(silk_tokens_decode(t.get(), &p, &m, stats));
    return Mesh(m);
  }
  silk_roundtrip_report Roundtrip(const silk_encode_params& p = silk_encode_default_params()) const {
    silk_roundtrip_report r = Sized<silk_roundtrip_report>();
    Check(silk_mesh_roundtrip(h_.get(), &p, &r));
    return r;
  }
  // Hole repair of a token stream (silk_tokens_repair); report_json (may be null) gets the report.
  static Mesh Repair(const Tokens& t, const silk_repair_params& p = silk_repair_default_params(),
                     silk_repair_stats* stats = nullptr, std::string* report_json = nullptr) {
    silk_mesh* m = nullptr;
    silk_report* r = nullptr;
    Check(silk_tokens_repair(t.get(), &p, &m, stats, report_json ? &r : nullptr));
    Mesh mesh(m);
    if (report_json) *report_json = TakeReport(r);
    return mesh;
  }
  // One random legal stream (silk_tokens_random_walk) and its mesh.
  static Mesh RandomWalk(const silk_random_walk_params& p, std::vector<int32_t>* ids) {
    silk_tokens* t = nullptr;
    silk_mesh* m = nullptr;
    Check(silk_tokens_random_walk(&p, &t, &m));
    Tokens tokens(t);
    Mesh mesh(m);
    if (ids) *ids = tokens.ids();
    return mesh;
  }
  const silk_mesh* get() const { return h_.get(); }

 private:
  std::unique_ptr<silk_mesh, MeshDeleter> h_;
};

struct ModelDeleter {
  void operator()(silk_model* m) const { silk_model_destroy(m); }
};
struct GeneratorDeleter {
  void operator()(silk_generator* g) const { silk_generator_destroy(g); }
};

// A loaded model folder (shareable between threads).
class Model {
 public:
  static Model Load(const std::string& dir, const silk_model_params& o = silk_model_default_params()) {
    silk_model* m = nullptr;
    Check(silk_model_load(dir.c_str(), &o, &m));
    return Model(m);
  }
  silk_model_info info() const {
    silk_model_info i = Sized<silk_model_info>();
    Check(silk_model_get_info(h_.get(), &i));
    return i;
  }
  const silk_model* get() const { return h_.get(); }

 private:
  explicit Model(silk_model* m) : h_(m) {}
  std::unique_ptr<silk_model, ModelDeleter> h_;
};

// Models by name (silk.h "models by name"): each returns a UTF-8 path or throws Error.
inline std::string ModelsDir(const char* name = nullptr) {
  const std::vector<char> v =
      CopyAll<char>([&](char* o, size_t c, size_t* n) { return silk_models_dir(name, o, c, n); });
  return std::string(v.data());
}
inline std::string ModelDefaultDir() {
  return std::string(
      CopyAll<char>([](char* o, size_t c, size_t* n) { return silk_model_default_dir(o, c, n); }).data());
}
inline std::string FindModel(const std::string& name_or_dir) {
  const std::vector<char> v =
      CopyAll<char>([&](char* o, size_t c, size_t* n) { return silk_model_find(name_or_dir.c_str(), o, c, n); });
  return std::string(v.data());
}
// silk_models_list's JSON.
inline std::string ModelsListJson() {
  silk_report* r = nullptr;
  Check(silk_models_list(&r));
  return TakeReport(r);
}

// One generation at a time; keep one per thread (it keeps its model alive).
class Generator {
 public:
  explicit Generator(const Model& model) {
    silk_generator* g = nullptr;
    Check(silk_generator_create(model.get(), &g));
    h_.reset(g);
  }
  silk_generator* get() const { return h_.get(); }
  // silk_generator_run. stats (may be NULL): its struct_size set by the caller (silk.h).
  Mesh Generate(const silk_generate_input& input, const silk_generate_params& p = silk_generate_default_params(),
                silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generator_run(h_.get(), &input, &p, &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
  }
  // From a mesh or a point-cloud mesh.
  Mesh Generate(const Mesh& input, const silk_generate_params& p = silk_generate_default_params(),
                silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_generate_input in{sizeof(silk_generate_input), input.get(), nullptr, 0};
    return Generate(in, p, stats, tokens);
  }
  // Step-wise (silk.h): Start, Advance until it returns true (done), Finish.
  void Start(const silk_generate_input& input, const silk_generate_params& p = silk_generate_default_params()) {
    Check(silk_generator_start(h_.get(), &input, &p));
  }
  bool Advance(int32_t max_ids, silk_advance_until until = SILK_ADVANCE_IDS) {
    int32_t done = 0;
    Check(silk_generator_advance(h_.get(), max_ids, until, &done));
    return done != 0;
  }
  void Cancel() { silk_generator_cancel(h_.get()); }
  Mesh MeshSoFar() {
    silk_mesh* m = nullptr;
    Check(silk_generator_get_mesh(h_.get(), &m));
    return Mesh(m);
  }
  silk_generate_stats Stats() {
    silk_generate_stats s{};
    s.struct_size = sizeof(s);
    Check(silk_generator_get_stats(h_.get(), &s));
    return s;
  }
  // Best of N's candidates of the generation in progress (C API 1.5): every one's state, and its mesh.
  std::vector<silk_candidate_info> Candidates() {
    int32_t n = 0;
    Check(silk_generator_candidate_count(h_.get(), &n));
    std::vector<silk_candidate_info> out(static_cast<size_t>(n));
    for (int32_t i = 0; i < n; ++i) {
      out[static_cast<size_t>(i)].struct_size = sizeof(silk_candidate_info);
      Check(silk_generator_get_candidate(h_.get(), i, &out[static_cast<size_t>(i)]));
    }
    return out;
  }
  Mesh CandidateMesh(int32_t index) {
    silk_mesh* m = nullptr;
    Check(silk_generator_get_candidate_mesh(h_.get(), index, &m));
    return Mesh(m);
  }
  Mesh Finish(silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generator_finish(h_.get(), &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
  }
  // The last finished generation as JSON (trace: with points and legal sets).
  std::string ReportJson(bool trace = false) {
    silk_report* r = nullptr;
    Check(silk_generator_report(h_.get(), trace ? 1 : 0, &r));
    return TakeReport(r);
  }
  // The encoder's points in the input frame: rows of x y z nx ny nz, flattened (silk_generator_copy_points).
  std::vector<double> Points() {
    return CopyAll<double>(
        [&](double* o, size_t c, size_t* n) { return silk_generator_copy_points(h_.get(), o, c, n); });
  }
  // points: rows of x y z nx ny nz.
  Mesh GenerateFromPoints(const std::vector<double>& points,
                          const silk_generate_params& p = silk_generate_default_params(),
                          silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_generate_input in{sizeof(silk_generate_input), nullptr, points.data(), points.size() / 6};
    return Generate(in, p, stats, tokens);
  }

 private:
  static Mesh Finish(silk_mesh* m, silk_tokens* t, std::vector<int32_t>* tokens) {
    Mesh mesh(m);
    if (tokens) *tokens = Tokens(t).ids();
    return mesh;
  }
  std::unique_ptr<silk_generator, GeneratorDeleter> h_;
};

}  // namespace silk_cpp
