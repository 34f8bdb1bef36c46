#include "watergen/caustics/caustics_reference.h"

#include <algorithm>
#include <cmath>

namespace watergen {

namespace {

struct Vec3 {
    double x, y, z;
};
Vec3 operator+(Vec3 a, Vec3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator*(double s, Vec3 a) {
    return {s * a.x, s * a.y, s * a.z};
}
double dot(Vec3 a, Vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3 normalize(Vec3 a) {
    return (1.0 / std::sqrt(dot(a, a))) * a;
}

// The surface point of parameter (x, z) and its unnormalised upward normal dP/dz x dP/dx.
struct SurfacePoint {
    Vec3 position, normal;
};

SurfacePoint surface_at(const std::vector<CausticsWave>& waves, double x, double z) {
    Vec3 p{x, 0, z}, dx{1, 0, 0}, dz{0, 0, 1};
    for (const CausticsWave& w : waves) {
        const double theta = w.frequency * (w.dir_x * x + w.dir_z * z) + w.phase;
        const double s = std::sin(theta), c = std::cos(theta);
        const double qa = w.steepness * w.amplitude;
        p = p + Vec3{qa * w.dir_x * c, w.amplitude * s, qa * w.dir_z * c};
        // d/dx and d/dz of the above: dtheta/dx = frequency dir_x, dtheta/dz = frequency dir_z.
        const Vec3 d{-qa * w.dir_x * s, w.amplitude * c, -qa * w.dir_z * s};
        dx = dx + (w.frequency * w.dir_x) * d;
        dz = dz + (w.frequency * w.dir_z) * d;
    }
    return {p, cross(dz, dx)};
}

// Unpolarised dielectric reflectance for light entering water from air.
double fresnel_reflectance(double cos_i, double ior) {
    const double sin_t2 = (1 - cos_i * cos_i) / (ior * ior);
    const double cos_t = std::sqrt(1 - sin_t2);
    const double rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t);
    const double rp = (ior * cos_i - cos_t) / (ior * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

std::string check(const CausticsSetup& s) {
    const auto& l = s.sun_direction;
    if (s.texels == 0 || s.photons_per_side == 0) return "texels and photons_per_side must be > 0";
    if (!(l[1] < 0)) return "sun_direction must point down (y < 0)";
    if (!(s.ior > 1)) return "ior must be > 1 (water under air)";
    if (!(s.depth >= 0)) return "depth must be >= 0";
    if (!(s.size > 0) || !(s.margin >= 0)) return "size must be > 0 and margin >= 0";
    return "";
}

} // namespace

double mean_intensity(const std::vector<double>& intensity) {
    double sum = 0;
    for (double v : intensity)
        sum += v;
    return intensity.empty() ? 0 : sum / double(intensity.size());
}

double CausticsImage::mean() const {
    return mean_intensity(intensity);
}

double CausticsImage::max() const {
    double m = 0;
    for (double v : intensity)
        m = std::fmax(m, v);
    return m;
}

double CausticsImage::standard_deviation() const {
    const double mu = mean();
    double sum = 0;
    for (double v : intensity)
        sum += (v - mu) * (v - mu);
    return intensity.empty() ? 0 : std::sqrt(sum / double(intensity.size()));
}

CausticsImage caustics_reference(const CausticsSetup& s, std::string* error) {
    CausticsImage out;
    if (std::string why = check(s); !why.empty()) {
        *error = why;
        return out;
    }
    const Vec3 light = normalize({s.sun_direction[0], s.sun_direction[1], s.sun_direction[2]});
    const double eta = 1.0 / s.ior;
    const uint32_t n = s.texels;
    out.texels = n;
    out.intensity.assign(size_t(n) * n, 0.0);

    // Photons on a regular grid of cell centres over the sampled area, `per_side` per texel
    // side: under flat water every texel receives the same number of photons exactly.
    const double texel = s.size / n;
    const double margin = s.periodic ? 0.0 : s.margin;
    const uint32_t margin_texels = uint32_t(std::ceil(margin / texel));
    const uint32_t side = (n + 2 * margin_texels) * s.photons_per_side;
    const double start_x = s.x0 - margin_texels * texel, start_z = s.z0 - margin_texels * texel;
    const double step = texel / s.photons_per_side;
    size_t shadowed = 0;
    for (uint32_t j = 0; j < side; ++j) {
        for (uint32_t i = 0; i < side; ++i) {
            const SurfacePoint p =
                surface_at(s.waves, start_x + (i + 0.5) * step, start_z + (j + 0.5) * step);
            double weight = -dot(p.normal, light) / -light.y;
            out.weight_sampled += weight;
            if (weight <= 0) {
                ++shadowed;
                continue;
            }
            // Refract (GLSL refract(I, N, eta)); air into water has no total reflection.
            const Vec3 normal = normalize(p.normal);
            const double cos_i = -dot(normal, light);
            const double k = 1 - eta * eta * (1 - cos_i * cos_i);
            const Vec3 t = eta * light + (eta * cos_i - std::sqrt(k)) * normal;
            const double length = (p.position.y + s.depth) / -t.y; // t is unit
            if (s.fresnel) weight *= 1 - fresnel_reflectance(cos_i, s.ior);
            if (s.attenuation > 0) weight *= std::exp(-s.attenuation * length);
            // Splatted bilinearly (a tent one texel wide each way): on flat water, whatever
            // the shift of the landing grid, every texel still receives exactly
            // photons_per_side^2 (the tent's samples at 1/m spacing sum to m), and on waves the
            // estimate is smooth instead of counting whole photon columns in or out.
            const double u = (p.position.x + length * t.x - s.x0) / texel - 0.5;
            const double v = (p.position.z + length * t.z - s.z0) / texel - 0.5;
            const double fu = std::floor(u), fv = std::floor(v);
            const double au = u - fu, av = v - fv;
            for (int dv = 0; dv < 2; ++dv)
                for (int du = 0; du < 2; ++du) {
                    long ti = long(fu) + du, tj = long(fv) + dv;
                    if (s.periodic) {
                        ti = ((ti % long(n)) + long(n)) % long(n);
                        tj = ((tj % long(n)) + long(n)) % long(n);
                    } else if (ti < 0 || tj < 0 || ti >= long(n) || tj >= long(n)) {
                        continue;
                    }
                    const double share = (du ? au : 1 - au) * (dv ? av : 1 - av);
                    out.intensity[size_t(tj) * n + size_t(ti)] += weight * share;
                }
        }
    }
    // Relative to flat water: per texel, photons_per_side^2 photons of weight 1.
    const double per_texel = double(s.photons_per_side) * s.photons_per_side;
    for (double& v : out.intensity)
        v /= per_texel;
    const double photons = double(side) * side;
    out.weight_sampled /= photons;
    out.shadowed = double(shadowed) / photons;
    return out;
}

namespace {

const std::vector<double>& value(const std::map<std::string, std::vector<double>>& values,
                                 const std::string& name) {
    static const std::vector<double> none;
    auto it = values.find(name);
    return it == values.end() ? none : it->second;
}

double scalar(const std::map<std::string, std::vector<double>>& values, const std::string& name,
              double fallback) {
    const auto& v = value(values, name);
    return v.empty() ? fallback : v[0];
}

} // namespace

CausticsSetup caustics_reference_setup(const std::string& model,
                                       const std::map<std::string, std::vector<double>>& values,
                                       uint32_t texels, double margin) {
    CausticsSetup s;
    const std::string f = model == "gerstner" ? "gerstner" : "waves";
    const int count = std::clamp(int(std::floor(scalar(values, f + "_wave_count", 0))), 0, 8);
    const double time = scalar(values, "time", 0);
    const std::vector<double>& directions = value(values, f + "_wave_directions");
    const std::vector<double>& speeds = value(values, f + "_wave_speeds");
    double a = scalar(values, f + "_amplitude", 0), w = scalar(values, f + "_frequency", 1);
    const double ga = scalar(values, f + "_amplitude_gain", 1);
    const double gf = scalar(values, f + "_frequency_gain", 1);
    const double q = scalar(values, "gerstner_steepness", 0);
    for (int i = 0; i < count && size_t(2 * i + 1) < directions.size() && size_t(i) < speeds.size();
         ++i) {
        CausticsWave wave;
        wave.amplitude = a;
        wave.frequency = w;
        wave.dir_x = directions[size_t(2 * i)];
        wave.dir_z = directions[size_t(2 * i + 1)];
        wave.phase = time * speeds[size_t(i)];
        // GPU Gems' Q_i = Q / (w_i A_i n) (the shader guards w_i A_i from 0 the same way).
        if (model == "gerstner") wave.steepness = q / (count * std::max(w * a, 1e-6));
        s.waves.push_back(wave);
        a *= ga;
        w *= gf;
    }
    const std::vector<double>& sun = value(values, "sun_direction");
    if (sun.size() == 3) s.sun_direction = {sun[0], sun[1], sun[2]};
    s.ior = scalar(values, "ior_water", 1.33333);
    s.depth = scalar(values, "caustics_depth", 5);
    const std::vector<double>& window = value(values, "caustics_window");
    if (window.size() == 3) {
        s.x0 = window[0];
        s.z0 = window[1];
        s.size = window[2];
    }
    s.texels = texels;
    s.periodic = false;
    s.margin = margin;
    return s;
}

} // namespace watergen
