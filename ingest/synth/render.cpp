#include "ingest/synth/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/geometry.hpp"

namespace smql::synth {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// ---- procedural texture ------------------------------------------------------

std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

// A value in [-1, 1] attached to one lattice point (a 32-bit integer hash: cheap, and
// plenty for a texture).
double latticeValue(std::uint32_t hx, std::uint32_t hy, std::uint32_t hz, std::uint32_t seed) {
    std::uint32_t x = seed ^ hx ^ hy ^ hz;
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return static_cast<double>(x) * (2.0 / 4294967296.0) - 1.0;
}

double smooth(double t) { return t * t * (3 - 2 * t); }

// Value noise: lattice values interpolated with a smoothstep, in [-1, 1].
double valueNoise(double x, double y, double z, std::uint64_t seed) {
    double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    auto ix = static_cast<std::uint32_t>(static_cast<std::int64_t>(fx)),
         iy = static_cast<std::uint32_t>(static_cast<std::int64_t>(fy)),
         iz = static_cast<std::uint32_t>(static_cast<std::int64_t>(fz));
    double tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
    const std::uint32_t hx[2] = {ix * 0x8da6b343U, (ix + 1) * 0x8da6b343U};
    const std::uint32_t hy[2] = {iy * 0xd8163841U, (iy + 1) * 0xd8163841U};
    const std::uint32_t hz[2] = {iz * 0xcb1ab31fU, (iz + 1) * 0xcb1ab31fU};
    const auto s = static_cast<std::uint32_t>(mix64(seed));
    double c[2][2][2];
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int d = 0; d < 2; ++d) c[a][b][d] = latticeValue(hx[a], hy[b], hz[d], s);
    auto lerp = [](double p, double q, double t) { return p + (q - p) * t; };
    double x00 = lerp(c[0][0][0], c[1][0][0], tx), x10 = lerp(c[0][1][0], c[1][1][0], tx);
    double x01 = lerp(c[0][0][1], c[1][0][1], tx), x11 = lerp(c[0][1][1], c[1][1][1], tx);
    return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
}

// ---- boxes -------------------------------------------------------------------

// Corner i of a box has local signs (bit 0: x, bit 1: y, bit 2: z).
constexpr std::array<std::array<int, 4>, 6> kFaces = {{
    {1, 3, 7, 5},  // +x
    {0, 4, 6, 2},  // -x
    {2, 6, 7, 3},  // +y
    {0, 1, 5, 4},  // -y
    {4, 5, 7, 6},  // +z
    {0, 2, 3, 1},  // -z
}};

struct Geometry {
    std::array<Vector3d, 8> corners;
    std::array<Vector3d, 6> normals;
    Vector3d axisX, axisY;
};

Geometry geometryOf(const model::Box& box) {
    Geometry g;
    double c = std::cos(box.yaw), s = std::sin(box.yaw);
    g.axisX = {c, s, 0};
    g.axisY = {-s, c, 0};
    Vector3d centre(box.center.x, box.center.y, box.center.z);
    for (int i = 0; i < 8; ++i) {
        double lx = (i & 1 ? 0.5 : -0.5) * box.size.x, ly = (i & 2 ? 0.5 : -0.5) * box.size.y,
               lz = (i & 4 ? 0.5 : -0.5) * box.size.z;
        g.corners[i] = centre + lx * g.axisX + ly * g.axisY + Vector3d(0, 0, lz);
    }
    g.normals = {g.axisX, -g.axisX, g.axisY, -g.axisY, Vector3d(0, 0, 1), Vector3d(0, 0, -1)};
    return g;
}

std::uint32_t surfaceSeed(model::NodeId id) { return static_cast<std::uint32_t>(mix64(id * 0x2545F4914F6CDD1DULL)); }

// The fixed light: from above, a little from the south-west.
const Vector3d kLight = Vector3d(0.35, 0.55, 1.0).normalized();
constexpr double kAmbient = 0.87, kDiffuse = 0.14;

struct Edge {
    double a, b, c;  // E(u, v) = a u + b v + c, >= 0 inside
    bool owned;      // pixels exactly on the edge belong to this polygon
};

struct FaceRef {
    int surface;
    int face;
};

std::uint8_t toByte(double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0) + 0.5); }

}  // namespace

double textureFactor(const model::Vec3& p, std::uint32_t seed, double footprint) {
    static constexpr std::array<double, 3> kWavelength = {0.025, 0.06, 0.15};
    static constexpr std::array<double, 3> kAmplitude = {0.3, 0.35, 0.35};
    // Each octave's lattice is turned away from the world axes (and from the other octaves'),
    // so that no grid lines up with the boxes' edges.
    static const std::array<Matrix3d, 3> kTurn = [] {
        std::array<Matrix3d, 3> turns;
        const double angles[3][3] = {{0.61, 0.37, 0.83}, {1.27, 0.71, 0.29}, {0.43, 1.09, 1.51}};
        for (int k = 0; k < 3; ++k)
            turns[k] = (Eigen::AngleAxisd(angles[k][0], Vector3d::UnitZ()) *
                        Eigen::AngleAxisd(angles[k][1], Vector3d::UnitX()) *
                        Eigen::AngleAxisd(angles[k][2], Vector3d::UnitY()))
                           .toRotationMatrix();
        return turns;
    }();
    double sum = 0;
    for (std::size_t k = 0; k < kWavelength.size(); ++k) {
        // Fade an octave out as its wavelength nears two pixels (no aliasing, same look from far away).
        double weight = std::clamp((kWavelength[k] / footprint - 2.0) / 2.0, 0.0, 1.0);
        if (weight <= 0) continue;
        Vector3d q = kTurn[k] * Vector3d(p.x, p.y, p.z) / kWavelength[k];
        sum += kAmplitude[k] * weight * valueNoise(q.x(), q.y(), q.z(), seed * 4ULL + k);
    }
    return 1.0 + 0.22 * std::clamp(1.8 * sum, -1.0, 1.0);
}

std::vector<Surface> surfacesOf(const model::SceneData& scene) {
    // The room's centre: the floor's, else the mean of all boxes.
    Vector3d centre(0, 0, 0);
    int count = 0;
    for (const model::Node& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        centre += Vector3d(n.box.center.x, n.box.center.y, n.box.center.z);
        ++count;
    }
    if (count) centre /= count;
    for (const model::Node& n : scene.nodes)
        if (n.kind == model::NodeKind::Anchor && n.category == "floor" && n.geometry != model::GeometryKind::None)
            centre = Vector3d(n.box.center.x, n.box.center.y, n.box.center.z);

    std::vector<Surface> out;
    for (const model::Node& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        if (n.id > 65535) throw std::invalid_argument("synth: node ids must fit 16-bit instance masks");
        Surface s;
        s.id = n.id;
        s.box = n.box;
        const std::string* color = n.attribute("color");
        std::optional<Rgb> named = color ? colorByName(*color) : std::nullopt;
        s.color = named ? *named : neutralColor(n.category);
        bool panel = n.kind == model::NodeKind::Anchor && (n.category == "door" || n.category == "window");
        if (panel) {
            s.look = n.category == "door" ? Look::Door : Look::Window;
            Geometry g = geometryOf(n.box);
            Vector3d normal = n.box.size.x < n.box.size.y ? g.axisX : g.axisY;
            Vector3d toCentre = centre - Vector3d(n.box.center.x, n.box.center.y, n.box.center.z);
            if (normal.dot(toCentre) < 0) normal = -normal;
            s.box.center.x += normal.x() * kPanelOffset;
            s.box.center.y += normal.y() * kPanelOffset;
        }
        out.push_back(s);
    }
    return out;
}

Renderer::Renderer(std::vector<Surface> surfaces) : surfaces_(std::move(surfaces)) {}

namespace {

// The z-buffer the faces are drawn into: per pixel the nearest inverse depth and which face is there.
struct Raster {
    int width = 0, height = 0;
    std::vector<double> inverseDepth;
    std::vector<std::int32_t> faceAt;
    std::vector<FaceRef> faces;
};

// One face of a box, its corners in camera coordinates (`cam`): clipped at the near plane, projected,
// and its pixels drawn where it is the nearest so far.
void rasteriseFace(const ingest::Intrinsics& K, const std::array<Vector3d, 8>& cam, const Vector3d& normalInCamera,
                   int fi, int surface, Raster& raster) {
    const auto& quad = kFaces[fi];
    // The crossing point is always computed from the inside end, so two faces sharing an edge get
    // the same point.
    std::array<Vector3d, 8> poly;
    int n = 0;
    for (int k = 0; k < 4; ++k) {
        const Vector3d& a = cam[quad[k]];
        const Vector3d& b = cam[quad[(k + 1) % 4]];
        bool aIn = a.z() >= kNearPlane, bIn = b.z() >= kNearPlane;
        if (aIn) poly[n++] = a;
        if (aIn != bIn) {
            const Vector3d& in = aIn ? a : b;
            const Vector3d& out = aIn ? b : a;
            double s = (kNearPlane - in.z()) / (out.z() - in.z());
            Vector3d p = in + s * (out - in);
            p.z() = kNearPlane;
            poly[n++] = p;
        }
    }
    if (n < 3) return;

    std::array<double, 8> xs, ys;
    double area = 0;
    for (int k = 0; k < n; ++k) {
        xs[k] = K.fx * (poly[k].x() / poly[k].z()) + K.cx;
        ys[k] = K.fy * (poly[k].y() / poly[k].z()) + K.cy;
    }
    for (int k = 0; k < n; ++k) area += xs[k] * ys[(k + 1) % n] - xs[(k + 1) % n] * ys[k];
    if (!(std::abs(area) > 1e-9)) return;
    if (area < 0) {
        std::reverse(xs.begin(), xs.begin() + n);
        std::reverse(ys.begin(), ys.begin() + n);
    }
    // Edge functions, positive inside. Two polygons sharing an edge get exactly negated
    // coefficients, and exactly one of them owns the pixels on it.
    std::array<Edge, 8> edges;
    for (int k = 0; k < n; ++k) {
        double x0 = xs[k], y0 = ys[k], x1 = xs[(k + 1) % n], y1 = ys[(k + 1) % n];
        Edge& e = edges[k];
        e.a = y0 - y1;
        e.b = x1 - x0;
        e.c = x0 * y1 - x1 * y0;
        e.owned = e.a > 0 || (e.a == 0 && e.b > 0);
    }
    // Inverse depth is affine in (u, v) on a plane: 1/z = (n . ray) / (n . p0), ray = (xn, yn, 1).
    const Vector3d& nc = normalInCamera;
    double dc = nc.dot(cam[quad[0]]);
    if (dc >= 0) return;
    const double ia = nc.x() / (K.fx * dc), ib = nc.y() / (K.fy * dc),
                 ic = (nc.z() - nc.x() * K.cx / K.fx - nc.y() * K.cy / K.fy) / dc;

    double minX = xs[0], maxX = xs[0], minY = ys[0], maxY = ys[0];
    for (int k = 1; k < n; ++k) {
        minX = std::min(minX, xs[k]), maxX = std::max(maxX, xs[k]);
        minY = std::min(minY, ys[k]), maxY = std::max(maxY, ys[k]);
    }
    int u0 = static_cast<int>(std::max(0.0, std::ceil(minX)));
    int u1 = static_cast<int>(std::min<double>(raster.width - 1, std::floor(maxX)));
    int v0 = static_cast<int>(std::max(0.0, std::ceil(minY)));
    int v1 = static_cast<int>(std::min<double>(raster.height - 1, std::floor(maxY)));
    if (u0 > u1 || v0 > v1) return;

    auto faceIndex = static_cast<std::int32_t>(raster.faces.size());
    raster.faces.push_back({surface, fi});
    for (int v = v0; v <= v1; ++v) {
        // A conservative span from the edges, then the exact test per pixel.
        double lo = u0, hi = u1;
        bool empty = false;
        for (int k = 0; k < n && !empty; ++k) {
            const Edge& e = edges[k];
            double rest = e.b * v + e.c;
            if (e.a > 0)
                lo = std::max(lo, std::floor(-rest / e.a) - 1);
            else if (e.a < 0)
                hi = std::min(hi, std::ceil(-rest / e.a) + 1);
            else if (rest < 0 || (rest == 0 && !e.owned))
                empty = true;
        }
        if (empty || lo > hi) continue;
        std::size_t row = static_cast<std::size_t>(v) * raster.width;
        for (int u = static_cast<int>(lo); u <= static_cast<int>(hi); ++u) {
            bool inside = true;
            for (int k = 0; k < n && inside; ++k) {
                const Edge& e = edges[k];
                double value = e.a * u + e.b * v + e.c;
                inside = !(value < 0 || (value == 0 && !e.owned));
            }
            if (!inside) continue;
            double iz = ia * u + ib * v + ic;
            if (iz > raster.inverseDepth[row + u]) {
                raster.inverseDepth[row + u] = iz;
                raster.faceAt[row + u] = faceIndex;
            }
        }
    }
}

// A pixel's colour from its world point, so textures stick to surfaces: plain surfaces textured,
// doors with grain, a frame and a handle, windows with a frame and a pale sky.
std::array<std::uint8_t, 3> shade(const Surface& surface, const Geometry& g, int face, const Vector3d& world,
                                  double footprint) {
    const Vector3d& normal = g.normals[face];
    double factor = kAmbient + kDiffuse * std::max(0.0, normal.dot(kLight));
    model::Vec3 p{world.x(), world.y(), world.z()};
    std::uint32_t seed = surfaceSeed(surface.id);
    double r = surface.color.r, gr = surface.color.g, b = surface.color.b;
    if (surface.look == Look::Plain) {
        factor *= textureFactor(p, seed, footprint);
    } else {
        // Panel coordinates: `along` the wall from the panel's centre, `up` from its bottom.
        const model::Box& box = surface.box;
        bool alongX = box.size.x >= box.size.y;
        double half = (alongX ? box.size.x : box.size.y) / 2, height = box.size.z;
        Vector3d d = world - Vector3d(box.center.x, box.center.y, box.center.z);
        double along = d.dot(alongX ? g.axisX : g.axisY);
        double up = world.z() - model::bottom(box);
        if (surface.look == Look::Door) {
            factor *= textureFactor({p.x, p.y, p.z * 0.15}, seed, footprint);
            if (std::abs(along) > half - 0.07 || up > height - 0.07) factor *= 0.82;
            if (along > half - 0.17 && along < half - 0.09 && std::abs(up - 1.0) < 0.025) r = 70, gr = 70, b = 75;
        } else {
            bool frameBar = std::abs(along) > half - 0.06 || up < 0.06 || up > height - 0.06 ||
                            std::abs(along) < 0.025 || std::abs(up - height / 2) < 0.025;
            if (frameBar) {
                r = 238, gr = 238, b = 232;
                factor *= textureFactor(p, seed, footprint * 2);
            } else {
                double s = std::clamp(up / height, 0.0, 1.0);
                r = 150 + 55 * s, gr = 185 + 40 * s, b = 220 + 20 * s;
                factor = 1.0 + 0.05 * valueNoise(p.x * 3, p.y * 3, p.z * 3, seed);
            }
        }
    }
    return {toByte(r * factor), toByte(gr * factor), toByte(b * factor)};
}

}  // namespace

RenderedFrame Renderer::render(const ingest::Intrinsics& K, const ingest::Pose& pose) const {
    const int W = K.width, H = K.height;
    Matrix3d R;
    R << pose.rotation[0], pose.rotation[1], pose.rotation[2], pose.rotation[3], pose.rotation[4], pose.rotation[5],
        pose.rotation[6], pose.rotation[7], pose.rotation[8];
    const Vector3d t(pose.translation.x, pose.translation.y, pose.translation.z);
    const Matrix3d Rt = R.transpose();

    Raster raster{W,
                  H,
                  std::vector<double>(static_cast<std::size_t>(W) * H, 0.0),
                  std::vector<std::int32_t>(static_cast<std::size_t>(W) * H, -1),
                  {}};
    std::vector<Geometry> geometries;
    geometries.reserve(surfaces_.size());
    for (std::size_t si = 0; si < surfaces_.size(); ++si) {
        geometries.push_back(geometryOf(surfaces_[si].box));
        const Geometry& g = geometries.back();
        std::array<Vector3d, 8> cam;
        for (int i = 0; i < 8; ++i) cam[i] = Rt * (g.corners[i] - t);
        for (int fi = 0; fi < 6; ++fi) {
            // Back faces (and faces seen edge-on) are never visible on a closed box.
            if (g.normals[fi].dot(t - g.corners[kFaces[fi][0]]) <= 0) continue;
            rasteriseFace(K, cam, Rt * g.normals[fi], fi, static_cast<int>(si), raster);
        }
    }

    RenderedFrame frame;
    frame.width = W;
    frame.height = H;
    frame.depth.assign(static_cast<std::size_t>(W) * H, 0.0f);
    frame.instance.assign(static_cast<std::size_t>(W) * H, 0);
    frame.rgb.assign(static_cast<std::size_t>(W) * H * 3, 0);
    for (int v = 0; v < H; ++v) {
        for (int u = 0; u < W; ++u) {
            std::size_t i = static_cast<std::size_t>(v) * W + u;
            if (raster.faceAt[i] < 0) continue;
            const FaceRef& ref = raster.faces[raster.faceAt[i]];
            const Surface& surface = surfaces_[ref.surface];
            const Geometry& g = geometries[ref.surface];
            double z = 1.0 / raster.inverseDepth[i];
            Vector3d ray((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
            frame.depth[i] = static_cast<float>(z);
            frame.instance[i] = static_cast<std::uint16_t>(surface.id);
            // Metres per pixel on the surface: grows with distance and with a grazing view.
            double cosine = std::abs(g.normals[ref.face].dot(R * ray.normalized()));
            double footprint = z * ray.norm() / K.fx / std::max(cosine, 0.2);
            auto rgb = shade(surface, g, ref.face, R * (ray * z) + t, footprint);
            std::copy(rgb.begin(), rgb.end(), &frame.rgb[i * 3]);
        }
    }
    return frame;
}

}  // namespace smql::synth
