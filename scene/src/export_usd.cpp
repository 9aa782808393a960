#include "pelage/scene/export_usd.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "hair_curves.h"
#include "pelage/fur/colors.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace fs = std::filesystem;

namespace {

std::string reason(int err) {
  if (err == ENOSPC) return "no space left on device (disk full)";
  if (err == EDQUOT) return "disk quota exceeded";
  if (err == EACCES || err == EPERM) return "permission denied";
  if (err == EROFS) return "read-only file system";
  return std::strerror(err);
}

std::atomic<unsigned> spoolCounter{0};

// One animated attribute's time samples, appended frame by frame to a file beside the output.
class Spool {
 public:
  Spool(const std::string& output, const std::string& tag) : output_(output) {
    const fs::path p(output);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    path_ = (dir / ("." + p.filename().string() + ".spool-" + tag + "-" +
                    std::to_string(::getpid()) + "-" + std::to_string(spoolCounter++)))
                .string();
    // Registered before it exists, so that a signal arriving at any moment after its creation
    // finds it (the handler unlinks it; unlinking a name not yet created is harmless).
    registerTemporary(path_);
    file_ = std::fopen(path_.c_str(), "w+b");
    if (!file_) {
      const int err = errno;
      unregisterTemporary(path_);
      inputError(output_, ": cannot write (", reason(err), ")");
    }
  }
  ~Spool() {
    if (file_) std::fclose(file_);
    std::remove(path_.c_str());
    unregisterTemporary(path_);
  }
  Spool(const Spool&) = delete;
  Spool& operator=(const Spool&) = delete;

  void write(const std::string& text) {
    if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size())
      fail(errno);
  }
  // Appends the spooled text to `out`.
  void copyTo(AtomicFileWriter& out) {
    if (std::fflush(file_) != 0) fail(errno);
    std::rewind(file_);
    std::vector<char> buf(1 << 20);
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), file_)) > 0) out.write(buf.data(), n);
    if (std::ferror(file_)) fail(errno ? errno : EIO);
  }

 private:
  [[noreturn]] void fail(int err) {
    inputError(output_, ": write failed (", reason(err), "); no file was written");
  }
  std::string output_;
  std::string path_;
  std::FILE* file_ = nullptr;
};

// Text output with numbers formatted exactly (shortest round-trip), handed on in large pieces.
class Text {
 public:
  explicit Text(Spool* spool = nullptr) : spool_(spool) { s_.reserve(kFlush + 256); }
  Text& operator<<(std::string_view v) {
    s_.append(v);
    maybeFlush();
    return *this;
  }
  Text& num(float v) {
    char b[32];
    const auto r = std::to_chars(b, b + sizeof b, v == 0.0f ? 0.0f : v);  // no "-0"
    s_.append(b, r.ptr);
    return *this;
  }
  Text& num(std::int64_t v) {
    char b[24];
    const auto r = std::to_chars(b, b + sizeof b, v);
    s_.append(b, r.ptr);
    return *this;
  }
  Text& tuple(const float* p) {
    s_ += '(';
    num(p[0]);
    s_ += ", ";
    num(p[1]);
    s_ += ", ";
    num(p[2]);
    s_ += ')';
    maybeFlush();
    return *this;
  }
  Text& tuple(const Eigen::Vector3f& v) { return tuple(v.data()); }
  void flush() {
    if (spool_) spool_->write(s_);
    if (spool_) s_.clear();
  }
  const std::string& str() const { return s_; }
  void clear() { s_.clear(); }

 private:
  static constexpr std::size_t kFlush = 1 << 20;
  void maybeFlush() {
    if (spool_ && s_.size() >= kFlush) flush();
  }
  Spool* spool_;
  std::string s_;
};

// "[(x, y, z), ...]" over n points, 8 per line.
template <class Get>
void pointArray(Text& t, std::int64_t n, Get get) {
  t << "[";
  for (std::int64_t i = 0; i < n; ++i) {
    if (i > 0) t << ((i % 8) == 0 ? ",\n                " : ", ");
    t.tuple(get(i));
  }
  t << "]";
}

void extentSample(Text& t, int frame, const Eigen::AlignedBox3f& box) {
  t << "            ";
  t.num(std::int64_t{frame}) << ": [";
  t.tuple(box.min()) << ", ";
  t.tuple(box.max()) << "],\n";
}

struct CoatOut {
  int coat = 0;
  std::string name;
  fur::HairLayout layout;
  fur::CoatShape shape;
  std::int64_t curves = 0;
  std::vector<float> widthScales;  // each hair's (HairBuffers::widthScales; empty: 1)
  std::unique_ptr<Spool> points, extent;
  float widthScaleOf(std::int64_t h) const {
    return widthScales.empty() ? 1.0f : widthScales[static_cast<std::size_t>(h)];
  }
};

std::string vec3Text(const Eigen::Vector3f& v) {
  Text t;
  t.tuple(v);
  return t.str();
}

}  // namespace

std::string usdIdentifier(const std::string& name) {
  std::string s = name.empty() ? std::string("_") : name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) c = '_';
  if (std::isdigit(static_cast<unsigned char>(s[0]))) s.insert(s.begin(), '_');
  return s;
}

struct UsdaWriter::Impl {
  std::string path;
  const Model* model = nullptr;
  const fur::FurParams* params = nullptr;
  const fur::FurColors* colors = nullptr;  // root k's colours (no culling: hair k is root k)
  UsdExportOptions options;
  std::unique_ptr<Spool> skinPoints, skinNormals, skinExtent;
  std::vector<CoatOut> coats;  // coats with hairs, known from the first frame
  int frames = 0;
  int lastAdded = -1;
  bool first = true;
  int removedTemporaries = 0;
  std::vector<float> curve, scratch;
};

UsdaWriter::UsdaWriter(std::string path, const Model& model, const Fur& fur,
                       const UsdExportOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = std::move(path);
  m.model = &model;
  m.params = &fur.params;
  m.colors = &fur.colors;
  m.options = options;
  PELAGE_CHECK(options.firstFrame <= options.lastFrame && options.framesPerSecond > 0.0);
  // Spools and temporaries an earlier run of the same output left when it was killed.
  const fs::path p(m.path);
  const std::string name = p.filename().string();
  m.removedTemporaries =
      removeStaleTemporaries(p.has_parent_path() ? p.parent_path().string() : std::string("."),
                             [&](const std::string& finalName) { return finalName == name; });
  m.skinPoints = std::make_unique<Spool>(m.path, "skin-points");
  m.skinNormals = std::make_unique<Spool>(m.path, "skin-normals");
  m.skinExtent = std::make_unique<Spool>(m.path, "skin-extent");
}

UsdaWriter::~UsdaWriter() = default;

int UsdaWriter::removedTemporaries() const {
  return impl_->removedTemporaries;
}

void UsdaWriter::addFrame(int frame, const FrameState& state) {
  Impl& m = *impl_;
  PELAGE_CHECK(frame >= m.options.firstFrame && frame <= m.options.lastFrame && frame > m.lastAdded,
               "frame ", frame, " after ", m.lastAdded, " in [", m.options.firstFrame, ", ",
               m.options.lastFrame, "]");
  PELAGE_CHECK(state.cpuFur, "UsdaWriter::addFrame needs the frame's CPU hairs");
  PELAGE_CHECK(state.skin.positions.size() ==
               static_cast<std::size_t>(m.model->skin.numVertices()));
  if (m.first) {
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(c)];
      if (b.drawn == 0) continue;
      CoatOut co;
      co.coat = c;
      co.name = c == fur::kOvercoat ? "overcoat" : "undercoat";
      co.layout = b.layout;
      co.shape = fur::makeCoatShape(*m.params, c);
      co.curves = b.drawn;
      co.widthScales = b.widthScales;
      co.points = std::make_unique<Spool>(m.path, co.name + "-points");
      co.extent = std::make_unique<Spool>(m.path, co.name + "-extent");
      m.coats.push_back(std::move(co));
    }
    m.first = false;
  }
  const auto key = [&](Text& t) {
    t << "            ";
    t.num(std::int64_t{frame}) << ": ";
  };

  // The skin.
  {
    const std::vector<Eigen::Vector3f>& p = state.skin.positions;
    const std::vector<Eigen::Vector3f>& n = state.skin.normals;
    Text t(m.skinPoints.get());
    key(t);
    pointArray(t, static_cast<std::int64_t>(p.size()),
               [&](std::int64_t i) { return p[static_cast<std::size_t>(i)].data(); });
    t << ",\n";
    t.flush();
    Text tn(m.skinNormals.get());
    key(tn);
    pointArray(tn, static_cast<std::int64_t>(n.size()),
               [&](std::int64_t i) { return n[static_cast<std::size_t>(i)].data(); });
    tn << ",\n";
    tn.flush();
    Text te(m.skinExtent.get());
    extentSample(te, frame, state.skinBounds);
    te.flush();
  }
  // The coats: every root's hair each frame (no culling), so the curve counts never change.
  for (CoatOut& co : m.coats) {
    const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(co.coat)];
    PELAGE_CHECK(b.drawn == co.curves, "coat ", co.name, " has ", b.drawn, " hairs in frame ",
                 frame, ", ", co.curves,
                 " in the first: export needs every hair in every frame (culling off)");
    const int V = co.layout.curveVertices();
    m.curve.resize(static_cast<std::size_t>(V) * 3);
    Eigen::AlignedBox3f box;
    Text t(co.points.get());
    key(t);
    t << "[";
    for (std::int64_t h = 0; h < b.drawn; ++h) {
      detail::hairCurve(b, co.shape, h, m.scratch, m.curve.data());
      for (int v = 0; v < V; ++v) {
        const std::int64_t i = h * V + v;
        if (i > 0) t << ((i % 8) == 0 ? ",\n                " : ", ");
        t.tuple(m.curve.data() + v * 3);
        box.extend(Eigen::Vector3f(m.curve[static_cast<std::size_t>(v) * 3],
                                   m.curve[static_cast<std::size_t>(v) * 3 + 1],
                                   m.curve[static_cast<std::size_t>(v) * 3 + 2]));
      }
    }
    t << "],\n";
    t.flush();
    // Widths reach half a tube diameter beyond the control points.
    const fur::StrandWidth& w = m.params->coats[static_cast<std::size_t>(co.coat)].width;
    float widest = 1.0f;
    for (float s : co.widthScales) widest = std::max(widest, s);
    const float pad = 0.5e-3f * std::max(w.rootMm, w.tipMm) * widest;
    if (!box.isEmpty()) {
      box.min().array() -= pad;
      box.max().array() += pad;
    }
    Text te(co.extent.get());
    extentSample(te, frame, box);
    te.flush();
  }
  m.lastAdded = frame;
  ++m.frames;
}

UsdExportCounts UsdaWriter::finish() {
  Impl& m = *impl_;
  PELAGE_CHECK(m.frames > 0, "UsdaWriter::finish without frames");
  const skin::SkinMesh& skin = m.model->skin;
  const std::string root = usdIdentifier(m.model->name);
  AtomicFileWriter out(m.path);
  Text t;
  auto emit = [&] {
    out.write(t.str());
    t.clear();
  };
  std::string doc = m.options.comment;
  std::replace(doc.begin(), doc.end(), '"', '\'');
  t << "#usda 1.0\n(\n    defaultPrim = \"" << root << "\"\n    doc = \"\"\"" << doc
    << "\"\"\"\n    endTimeCode = ";
  t.num(std::int64_t{m.options.lastFrame}) << "\n    framesPerSecond = ";
  t.num(static_cast<float>(m.options.framesPerSecond))
      << "\n    metersPerUnit = 1\n    startTimeCode = ";
  t.num(std::int64_t{m.options.firstFrame}) << "\n    timeCodesPerSecond = ";
  t.num(static_cast<float>(m.options.framesPerSecond)) << "\n    upAxis = \"Z\"\n)\n\n";
  t << "def Xform \"" << root << "\" (\n    kind = \"component\"\n)\n{\n";
  // Skin.
  t << "    def Mesh \"skin\"\n    {\n        uniform token orientation = \"rightHanded\"\n"
       "        uniform token subdivisionScheme = \"none\"\n        int[] faceVertexCounts = [";
  for (int f = 0; f < skin.numTriangles(); ++f) {
    t << (f == 0 ? "" : ((f % 32) == 0 ? ",\n            " : ", ")) << "3";
    if (t.str().size() > (1u << 20)) emit();
  }
  t << "]\n        int[] faceVertexIndices = [";
  for (std::size_t i = 0; i < skin.triangles.size(); ++i) {
    if (i > 0) t << ((i % 24) == 0 ? ",\n            " : ", ");
    t.num(std::int64_t{skin.triangles[i]});
    if (t.str().size() > (1u << 20)) emit();
  }
  t << "]\n        color3f[] primvars:displayColor = [" << vec3Text(srgbToLinear(skin.color))
    << "] (\n            interpolation = \"constant\"\n        )\n";
  t << "        float3[] extent.timeSamples = {\n";
  emit();
  m.skinExtent->copyTo(out);
  t << "        }\n        point3f[] points.timeSamples = {\n";
  emit();
  m.skinPoints->copyTo(out);
  t << "        }\n        normal3f[] normals (\n            interpolation = \"vertex\"\n        "
       ")\n"
       "        normal3f[] normals.timeSamples = {\n";
  emit();
  m.skinNormals->copyTo(out);
  t << "        }\n    }\n";
  // Coats.
  UsdExportCounts counts;
  for (CoatOut& co : m.coats) {
    const fur::CoatParams& cp = m.params->coats[static_cast<std::size_t>(co.coat)];
    const int V = co.layout.curveVertices();
    // One value per curve vertex, write(h, a) for hair h at a in [0, 1] along it (root to tip).
    const auto perVertex = [&](const auto& write) {
      for (std::int64_t h = 0; h < co.curves; ++h) {
        for (int k = 0; k < V; ++k) {
          if (h > 0 || k > 0) t << ((k == 0 && h % 8 == 0) ? ",\n            " : ", ");
          write(h, V > 1 ? static_cast<float>(k) / static_cast<float>(V - 1) : 0.0f);
        }
        if (t.str().size() > (1u << 20)) emit();
      }
    };
    t << "\n    def BasisCurves \"" << co.name << "\"\n    {\n";
    switch (co.layout.basis) {
      case fur::CurveBasis::Bezier:
        t << "        uniform token basis = \"bezier\"\n        uniform token type = \"cubic\"\n";
        break;
      case fur::CurveBasis::Linear:
        t << "        uniform token type = \"linear\"\n";
        break;
    }
    t << "        uniform token wrap = \"nonperiodic\"\n        int[] curveVertexCounts = [";
    for (std::int64_t h = 0; h < co.curves; ++h) {
      if (h > 0) t << ((h % 32) == 0 ? ",\n            " : ", ");
      t.num(std::int64_t{V});
      if (t.str().size() > (1u << 20)) emit();
    }
    // Colours (linear, as USD's are): the coat's one colour, or each hair's root and tip colours
    // graded over its V curve vertices.
    const fur::CoatColors& cc = m.colors->coats[static_cast<std::size_t>(co.coat)];
    t << "]\n        color3f[] primvars:displayColor = [";
    if (!cc.perHair) {
      t.tuple(cc.diffuse);
    } else {
      PELAGE_CHECK(cc.packed.size() == static_cast<std::size_t>(2 * co.curves),
                   "every root's hair is exported");
      perVertex([&](std::int64_t h, float a) { t.tuple(fur::hairColorAt(cc, h, a)); });
    }
    t << "] (\n            interpolation = \"" << (cc.perHair ? "vertex" : "constant")
      << "\"\n        )\n";
    if (co.layout.topology == fur::HairTopology::Rings) {
      // The tube's diameter at each segment end ("varying"): the coat's width there, tapering to
      // the tip (fur::StrandWidth, as the PLY and glb exports write it).
      const int ends = (V - 1) / 3 + 1;
      t << "        float[] widths = [";
      for (std::int64_t h = 0; h < co.curves; ++h)
        for (int e = 0; e < ends; ++e) {
          const std::int64_t i = h * ends + e;
          if (i > 0) t << ((i % 16) == 0 ? ",\n            " : ", ");
          const int k = ends == 2 ? (e == 0 ? 0 : co.shape.curvePoints - 1) : e;
          t.num(cp.width.metersAt(co.layout.along(k * co.layout.ringSides)) * co.widthScaleOf(h));
          if (t.str().size() > (1u << 20)) emit();
        }
      t << "] (\n            interpolation = \"varying\"\n        )\n";
    } else {
      // The hair's width at each vertex (fur::StrandWidth), tapering from root to tip.
      t << "        float[] widths = [";
      perVertex([&](std::int64_t h, float a) { t.num(cp.width.metersAt(a) * co.widthScaleOf(h)); });
      t << "] (\n            interpolation = \"vertex\"\n        )\n";
    }
    t << "        float3[] extent.timeSamples = {\n";
    emit();
    co.extent->copyTo(out);
    t << "        }\n        point3f[] points.timeSamples = {\n";
    emit();
    co.points->copyTo(out);
    t << "        }\n    }\n";
    counts.curves[co.coat] = co.curves;
    counts.verticesPerCurve[co.coat] = V;
  }
  t << "}\n";
  emit();
  out.commit();
  m.skinPoints.reset();
  m.skinNormals.reset();
  m.skinExtent.reset();
  for (CoatOut& co : m.coats) {
    co.points.reset();
    co.extent.reset();
  }
  counts.frames = m.frames;
  counts.skinVertices = skin.numVertices();
  counts.skinTriangles = skin.numTriangles();
  return counts;
}

}  // namespace pelage::scene
