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
    std::vector<int32_t> v(silk_tokens_count(h_.get()));
    if (!v.empty()) Check(silk_tokens_copy(h_.get(), v.data(), v.size()));
    return v;
  }
  void Save(const std::string& path) const { Check(silk_tokens_save(h_.get(), path.c_str())); }
  size_t size() const { return silk_tokens_count(h_.get()); }
  // The grammar's verdict (a rejection is a result, not an exception).
  silk_check_result GrammarCheck(const silk_check_params& p = silk_check_default_params()) const {
    silk_check_result r;
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
    Check(silk_mesh_load_with_params(path.c_str(), &p, &m));
    return Mesh(m);
  }
  void Save(const std::string& path, const silk_save_params& p = silk_save_default_params()) const {
    Check(silk_mesh_save_with_params(h_.get(), path.c_str(), &p));
  }
  size_t vertex_count() const { return silk_mesh_vertex_count(h_.get()); }
  size_t triangle_count() const { return silk_mesh_triangle_count(h_.get()); }
  bool is_point_cloud() const { return silk_mesh_has_normals(h_.get()) && triangle_count() == 0; }
  std::vector<double> positions() const {
    std::vector<double> v(3 * silk_mesh_vertex_count(h_.get()));
    if (!v.empty()) Check(silk_mesh_copy_positions(h_.get(), v.data(), v.size()));
    return v;
  }
  std::vector<int32_t> triangles() const {
    std::vector<int32_t> v(3 * silk_mesh_triangle_count(h_.get()));
    if (!v.empty()) Check(silk_mesh_copy_triangles(h_.get(), v.data(), v.size()));
    return v;
  }
  std::vector<int32_t> triangle_components() const {
    std::vector<int32_t> v(silk_mesh_triangle_count(h_.get()));
    if (!v.empty()) Check(silk_mesh_copy_triangle_components(h_.get(), v.data(), v.size()));
    return v;
  }
  Tokens Encode(const silk_encode_params& p = silk_encode_default_params(), silk_encode_stats* stats = nullptr) const {
    silk_tokens* t = nullptr;
    Check(silk_encode(h_.get(), &p, &t, stats));
    return Tokens(t);
  }
  static Mesh Decode(const Tokens& t, const silk_decode_params& p = silk_decode_default_params(),
                     silk_decode_stats* stats = nullptr) {
    silk_mesh* m = nullptr;
    Check(silk_decode_with_stats(t.get(), &p, &m, stats));
    return Mesh(m);
  }
  silk_roundtrip_report Roundtrip(const silk_encode_params& p = silk_encode_default_params()) const {
    silk_roundtrip_report r;
    Check(silk_roundtrip(h_.get(), &p, &r));
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
  static Model Load(const std::string& dir, const silk_model_options& o = silk_model_default_options()) {
    silk_model* m = nullptr;
    Check(silk_model_load(dir.c_str(), &o, &m));
    return Model(m);
  }
  silk_model_info info() const {
    silk_model_info i;
    Check(silk_model_get_info(h_.get(), &i));
    return i;
  }
  const silk_model* get() const { return h_.get(); }

 private:
  explicit Model(silk_model* m) : h_(m) {}
  std::unique_ptr<silk_model, ModelDeleter> h_;
};

// One generation at a time; keep one per thread (it keeps its model alive).
class Generator {
 public:
  explicit Generator(const Model& model) {
    silk_generator* g = nullptr;
    Check(silk_generator_create(model.get(), &g));
    h_.reset(g);
  }
  Mesh Generate(const Mesh& input, const silk_generate_params& p = silk_generate_default_params(),
                silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generate(h_.get(), input.get(), &p, &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
  }
  Mesh Generate(const silk_generate_input& input, const silk_generate_params& p = silk_generate_default_params(),
                silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generate_input_run(h_.get(), &input, &p, &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
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
    Check(silk_generator_mesh(h_.get(), &m));
    return Mesh(m);
  }
  silk_generate_stats Stats() {
    silk_generate_stats s;
    Check(silk_generator_stats(h_.get(), &s));
    return s;
  }
  Mesh Finish(silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generator_finish(h_.get(), &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
  }
  // The last finished generation as JSON (trace: with points and legal sets).
  std::string ReportJson(bool trace = false) {
    size_t size = 0;
    silk_status s = silk_generator_report_json(h_.get(), trace ? 1 : 0, nullptr, 0, &size);
    if (s != SILK_ERR_BUFFER_TOO_SMALL) Check(s);
    std::string out(size, '\0');
    Check(silk_generator_report_json(h_.get(), trace ? 1 : 0, &out[0], out.size(), &size));
    out.resize(size ? size - 1 : 0);
    return out;
  }
  // The encoder's points in the input frame: rows of x y z nx ny nz, flattened (silk_generator_points).
  std::vector<double> Points() {
    size_t rows = 0;
    silk_status s = silk_generator_points(h_.get(), nullptr, 0, &rows);
    if (s != SILK_ERR_BUFFER_TOO_SMALL) Check(s);
    std::vector<double> out(rows * 6);
    if (rows) Check(silk_generator_points(h_.get(), out.data(), out.size(), &rows));
    return out;
  }
  // points: rows of x y z nx ny nz.
  Mesh GenerateFromPoints(const std::vector<double>& points,
                          const silk_generate_params& p = silk_generate_default_params(),
                          silk_generate_stats* stats = nullptr, std::vector<int32_t>* tokens = nullptr) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    Check(silk_generate_from_points(h_.get(), points.data(), points.size() / 6, &p, &m, tokens ? &t : nullptr, stats));
    return Finish(m, t, tokens);
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
