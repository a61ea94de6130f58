#include <drape/render/renderer.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/vertex_normals.hpp>

#include <Eigen/Geometry>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sampling.hpp"

namespace drape::render {

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kInf = std::numeric_limits<float>::infinity();

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Filmic tone curve: Narkowicz's 2015 fit of the ACES reference rendering transform.
double tonemap(double x) {
    x = std::max(0.0, x);
    return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

std::uint8_t to_byte(double srgb) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(srgb, 0.0, 1.0) * 255.0));
}

Eigen::Vector3d display(const Eigen::Vector3d& linear, double exposure) {
    Eigen::Vector3d out;
    for (int k = 0; k < 3; ++k) out[k] = linear_to_srgb(tonemap(exposure * linear[k]));
    return out;
}

}  // namespace

bool RenderOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    std::ostringstream os;
    if (samples_per_pixel < 1 || samples_per_pixel > 4096) {
        os << "samples_per_pixel must be in 1..4096, got " << samples_per_pixel;
        return fail(os.str());
    }
    if (threads < 0) {
        os << "threads must be >= 0 (0 = all), got " << threads;
        return fail(os.str());
    }
    if (!background_srgb.allFinite() || background_srgb.minCoeff() < 0 || background_srgb.maxCoeff() > 1) {
        os << "background_srgb must hold three numbers in [0, 1], got " << background_srgb.transpose();
        return fail(os.str());
    }
    if (!(occlusion_distance_m > 0)) {
        os << "occlusion_distance_m must be positive, got " << occlusion_distance_m;
        return fail(os.str());
    }
    return true;
}

std::string RenderSummary::brief_report() const {
    std::ostringstream os;
    os << (termination == RenderTermination::rendered ? "rendered" : "cancelled") << " "
       << width_px << "x" << height_px << " px, " << samples_per_pixel << " spp, " << triangles
       << " triangles, " << rays << " rays, BVH " << build_seconds << " s, trace " << trace_seconds
       << " s on " << threads << " threads";
    if (!message.empty()) os << ": " << message;
    return os.str();
}

struct Renderer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Mesh> meshes;  ///< user meshes, then the stage; index = Embree geometry id
    /// Per mesh: linear colour and print colour (sRGB decoding once, not per sample).
    std::vector<std::array<Eigen::Vector3d, 2>> linear_colours;
    size_t user_meshes = 0;
    long long triangles = 0;
    double build_seconds = 0.0;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }

    void build();
    bool occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, float tfar) const;
    bool intersect(const Ray& ray, RTCRayHit& rh) const;
    Eigen::Vector3d shade(const RTCRayHit& rh, const Ray& ray, const Lighting& lighting,
                          const Eigen::Vector3d& sun_dir, double sun_tan_radius, const Eigen::Vector3d& fill_dir,
                          const RenderOptions& options, const detail::PixelSampler& sampler,
                          int sample, long long& rays) const;
};

void Renderer::Impl::build() {
    const auto t0 = Clock::now();
    // One build thread: Embree's BVH (and so the traversal order deciding ties between
    // triangles sharing an edge) is then the same whatever the machine.
    device = rtcNewDevice("threads=1");
    if (!device) throw std::runtime_error("Embree: cannot create a device (unsupported CPU?)");
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);  // no cracks between adjacent triangles
    for (const Mesh& m : meshes) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), static_cast<size_t>(m.V.rows())));
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), static_cast<size_t>(m.F.rows())));
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            throw std::runtime_error("Embree: out of memory for mesh '" + m.name + "'");
        }
        for (Eigen::Index i = 0; i < m.V.rows(); ++i)
            for (int k = 0; k < 3; ++k) vb[3 * i + k] = static_cast<float>(m.V(i, k));
        for (Eigen::Index f = 0; f < m.F.rows(); ++f)
            for (int k = 0; k < 3; ++k) ib[3 * f + k] = static_cast<unsigned>(m.F(f, k));
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);  // ids are assigned 0, 1, 2, ... in order
        rtcReleaseGeometry(g);
        triangles += m.F.rows();
    }
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: building the scene failed");
    build_seconds = seconds_since(t0);
}

bool Renderer::Impl::intersect(const Ray& ray, RTCRayHit& rh) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rh.ray.org_x = static_cast<float>(ray.origin.x());
    rh.ray.org_y = static_cast<float>(ray.origin.y());
    rh.ray.org_z = static_cast<float>(ray.origin.z());
    rh.ray.dir_x = static_cast<float>(ray.direction.x());
    rh.ray.dir_y = static_cast<float>(ray.direction.y());
    rh.ray.dir_z = static_cast<float>(ray.direction.z());
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = kInf;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

bool Renderer::Impl::occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = static_cast<float>(origin.x());
    r.org_y = static_cast<float>(origin.y());
    r.org_z = static_cast<float>(origin.z());
    r.dir_x = static_cast<float>(dir.x());
    r.dir_y = static_cast<float>(dir.y());
    r.dir_z = static_cast<float>(dir.z());
    r.tnear = 0.0f;
    r.tfar = tfar;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

Eigen::Vector3d Renderer::Impl::shade(const RTCRayHit& rh, const Ray& ray, const Lighting& lighting,
                                      const Eigen::Vector3d& sun_dir, double sun_tan_radius, const Eigen::Vector3d& fill_dir,
                                      const RenderOptions& options, const detail::PixelSampler& sampler,
                                      int sample, long long& rays) const {
    const Mesh& m = meshes[rh.hit.geomID];
    const Eigen::Index f = rh.hit.primID;
    const double u = rh.hit.u, v = rh.hit.v, w = 1.0 - u - v;
    const int i0 = m.F(f, 0), i1 = m.F(f, 1), i2 = m.F(f, 2);
    const Eigen::Vector3d P = ray.origin + static_cast<double>(rh.ray.tfar) * ray.direction;

    Eigen::Vector3d Ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    Ng.normalize();
    if (Ng.dot(ray.direction) > 0) Ng = -Ng;  // two-sided: face the viewer
    Eigen::Vector3d N = (w * m.N.row(i0) + u * m.N.row(i1) + v * m.N.row(i2)).transpose();
    if (N.dot(Ng) < 0) N = -N;
    N = N.norm() > 1e-12 ? N.normalized() : Ng;

    const Eigen::Vector2d uv =
        m.UV.size() == 0 ? Eigen::Vector2d(P.x(), P.y())
                         : Eigen::Vector2d((w * m.UV.row(i0) + u * m.UV.row(i1) + v * m.UV.row(i2)).transpose());
    const Eigen::Vector3d albedo =
        !m.material.texture.empty() ? texture_at(m.material, uv)
                                    : linear_colours[rh.hit.geomID][print_second_colour(m.material.print, uv) ? 1 : 0];
    // Shadow and sky rays start from the point the smooth normals describe (the shadow
    // terminator correction of Hanika, Ray Tracing Gems II, 2021): P projected onto the three
    // vertices' tangent planes, blended by the barycentrics, when that lies in front of the
    // flat triangle. From the
    // flat triangle itself, a coarse surface lit at a grazing angle shadows itself in
    // triangle-shaped dark patches the smooth shading does not explain. Then an offset
    // against self-intersection, scaled to single-precision resolution at P.
    Eigen::Vector3d Ps = P;
    {
        Eigen::Vector3d Pt = Eigen::Vector3d::Zero();
        const int corner[3] = {i0, i1, i2};
        const double weight[3] = {w, u, v};
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d pk = m.V.row(corner[k]).transpose(), nk = m.N.row(corner[k]).transpose();
            Pt += weight[k] * (P - (P - pk).dot(nk) * nk);
        }
        if ((Pt - P).dot(Ng) > 0 && Pt.allFinite()) Ps = Pt;
    }
    const Eigen::Vector3d Po = Ps + Ng * (2e-4 * std::max(1.0, P.cwiseAbs().maxCoeff()));
    const Eigen::Vector3d V = -ray.direction;

    Eigen::Vector3d out = Eigen::Vector3d::Zero();
    // Sun: one direction on the sun's disk per sample: soft shadow edges.
    const Eigen::Vector3d L = detail::cone_sample(sun_dir, sun_tan_radius, sampler.get(sample, 1));
    const double cos_l = N.dot(L);
    if (cos_l > 0 && Ng.dot(L) > 0 && lighting.sun_colour.maxCoeff() > 0) {
        ++rays;
        if (!occluded(Po, L, kInf)) {
            const double rough = m.material.roughness;
            const double shininess = 4.0 + 120.0 * (1.0 - rough) * (1.0 - rough);
            const double ks = 0.03 + 0.12 * (1.0 - rough);
            const Eigen::Vector3d H = (L + V).normalized();
            const double spec = ks * (shininess + 8.0) / (8.0 * detail::kPi) *
                                std::pow(std::max(0.0, N.dot(H)), shininess);
            out += lighting.sun_colour.cwiseProduct(albedo * cos_l + Eigen::Vector3d::Constant(spec * cos_l));
        }
    }
    // Sky: one cosine-weighted direction per sample; blocked directions see the bounce light.
    const Eigen::Vector3d D = detail::cosine_hemisphere(N, sampler.get(sample, 2));
    bool open = Ng.dot(D) > 0;
    if (open) {
        ++rays;
        open = !occluded(Po, D, static_cast<float>(options.occlusion_distance_m));
    }
    out += albedo.cwiseProduct(open ? lighting.sky(D) : lighting.bounce);
    out += albedo.cwiseProduct(lighting.fill_colour) * std::max(0.0, N.dot(fill_dir));
    return out;
}

Renderer::Renderer(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    scene.validate();
    impl_->meshes = scene.meshes;
    impl_->user_meshes = scene.meshes.size();
    for (Mesh& m : impl_->meshes) {
        if (m.smooth_subdivisions > 0) m = phong_tessellate(m, m.smooth_subdivisions);
        if (m.N.size() == 0) m.N = core::vertex_normals(m.V, m.F);
    }
    for (Mesh& m : stage_meshes(scene)) impl_->meshes.push_back(std::move(m));
    for (const Mesh& m : impl_->meshes)
        impl_->linear_colours.push_back({srgb_to_linear(m.material.colour_srgb),
                                         srgb_to_linear(m.material.print.second_colour_srgb)});
    impl_->build();
}

Renderer::~Renderer() = default;

long long Renderer::triangle_count() const { return impl_->triangles; }
double Renderer::build_seconds() const { return impl_->build_seconds; }

RenderSummary Renderer::render(const Camera& camera, const Lighting& lighting, const RenderOptions& options,
                               RenderImages& out, RenderProgress progress, void* progress_user) const {
    std::string why;
    require(camera.is_valid(&why), "render: ", why);
    require(lighting.is_valid(&why), "render: ", why);
    require(options.is_valid(&why), "render: ", why);

    const int W = camera.width_px, H = camera.height_px, spp = options.samples_per_pixel;
    out.colour.create(H, W, CV_8UC3);
    out.foreground.create(H, W, CV_8UC3);
    out.alpha.create(H, W, CV_8UC1);
    out.labels.create(H, W, CV_8UC1);
    out.mesh_index.create(H, W, CV_16SC1);
    out.depth.create(H, W, CV_32FC1);

    const Eigen::Vector3d sun_dir = lighting.sun_direction.normalized();
    const Eigen::Vector3d fill_dir = lighting.fill_direction.normalized();
    const double sun_tan_radius = std::tan(lighting.sun_angular_radius_rad);
    const Eigen::Vector3d bg = options.background_srgb;

    const Impl& impl = *impl_;
    auto render_pixel = [&](int x, int y, long long& rays) {
        RTCRayHit rh;
        // Label, mesh and depth maps: what the pixel centre sees (no blending of ids).
        const Ray centre = camera.ray(x + 0.5, y + 0.5);
        ++rays;
        if (impl.intersect(centre, rh)) {
            const unsigned g = rh.hit.geomID;
            out.labels.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(impl.meshes[g].label);
            out.mesh_index.at<std::int16_t>(y, x) =
                g < impl.user_meshes ? static_cast<std::int16_t>(std::min<unsigned>(g, 32767)) : std::int16_t(-1);
            out.depth.at<float>(y, x) = rh.ray.tfar;
        } else {
            out.labels.at<std::uint8_t>(y, x) = 0;
            out.mesh_index.at<std::int16_t>(y, x) = -1;
            out.depth.at<float>(y, x) = kInf;
        }
        const detail::PixelSampler sampler(x, y, spp);
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        int hits = 0;
        for (int s = 0; s < spp; ++s) {
            const Eigen::Vector2d j = spp == 1 ? Eigen::Vector2d(0.5, 0.5) : sampler.get(s, 0);
            const Ray ray = camera.ray(x + j.x(), y + j.y());
            ++rays;
            if (!impl.intersect(ray, rh)) continue;
            ++hits;
            sum += impl.shade(rh, ray, lighting, sun_dir, sun_tan_radius, fill_dir, options, sampler, s, rays);
        }
        const double a = static_cast<double>(hits) / spp;
        const Eigen::Vector3d fg = hits > 0 ? display(sum / hits, lighting.exposure) : Eigen::Vector3d::Zero();
        const Eigen::Vector3d c = a * fg + (1.0 - a) * bg;
        out.foreground.at<cv::Vec3b>(y, x) = cv::Vec3b(to_byte(fg.z()), to_byte(fg.y()), to_byte(fg.x()));
        out.colour.at<cv::Vec3b>(y, x) = cv::Vec3b(to_byte(c.z()), to_byte(c.y()), to_byte(c.x()));
        out.alpha.at<std::uint8_t>(y, x) = to_byte(a);
    };

    RenderSummary summary;
    summary.width_px = W;
    summary.height_px = H;
    summary.samples_per_pixel = spp;
    summary.triangles = impl.triangles;
    summary.build_seconds = impl.build_seconds;
    summary.threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
    std::atomic<long long> rays{0};
    const auto t0 = Clock::now();
    tbb::task_arena arena(summary.threads);
    // Bands of rows so that progress (and cancellation) is reported from this thread.
    constexpr int kTile = 16, kBand = 64;
    for (int y0 = 0; y0 < H; y0 += kBand) {
        const int y1 = std::min(H, y0 + kBand);
        const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (y1 - y0 + kTile - 1) / kTile;
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& r) {
                long long local = 0;
                for (int t = r.begin(); t < r.end(); ++t) {
                    const int tx = (t % tiles_x) * kTile, ty = y0 + (t / tiles_x) * kTile;
                    for (int y = ty; y < std::min(y1, ty + kTile); ++y)
                        for (int x = tx; x < std::min(W, tx + kTile); ++x) render_pixel(x, y, local);
                }
                rays += local;
            });
        });
        if (progress && !progress(static_cast<double>(y1) / H, progress_user)) {
            summary.termination = RenderTermination::cancelled;
            summary.message = "cancelled by the progress callback after row " + std::to_string(y1);
            break;
        }
    }
    summary.rays = rays.load();
    summary.trace_seconds = seconds_since(t0);
    return summary;
}

RenderSummary render(const Scene& scene, const Camera& camera, const Lighting& lighting,
                     const RenderOptions& options, RenderImages& out) {
    return Renderer(scene).render(camera, lighting, options, out);
}

}  // namespace drape::render
