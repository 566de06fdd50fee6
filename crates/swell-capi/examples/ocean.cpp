// swell from C++: the same C API behind a small RAII wrapper that turns result codes into
// exceptions. A floating object's height per frame, the displaced mesh, and a rendered frame.
//
// Build and run (from the repository root, after `cargo build --release -p swell-capi`):
//   c++ -std=c++17 -I crates/swell-capi/include crates/swell-capi/examples/ocean.cpp -L target/release -lswell -o ocean_cpp
//   LD_LIBRARY_PATH=target/release ./ocean_cpp
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "swell.h"

namespace {

void check(SwellResult r) {
    if (r != SWELL_RESULT_OK) throw std::runtime_error(swell_last_error_message());
}

struct WaterDeleter {
    void operator()(SwellWater *w) const { swell_water_destroy(w); }
};
struct SceneDeleter {
    void operator()(SwellScene *s) const { swell_scene_destroy(s); }
};

class Water {
  public:
    explicit Water(const std::string &toml) {
        SwellWater *w = nullptr;
        check(swell_water_from_toml(toml.c_str(), &w));
        handle_.reset(w);
        check(swell_water_grid_size(handle_.get(), &rows_, &cols_));
    }
    size_t rows() const { return rows_; }
    size_t cols() const { return cols_; }
    // Positions and normals, 3 floats per vertex, row-major.
    void displace(double t, std::vector<float> &positions, std::vector<float> &normals) {
        positions.resize(3 * rows_ * cols_);
        normals.resize(3 * rows_ * cols_);
        check(swell_water_displace(handle_.get(), t, positions.data(), positions.size(), normals.data(),
                                   normals.size()));
    }
    std::vector<float> heights(double t, const std::vector<float> &xz) {
        std::vector<float> out(xz.size() / 2);
        check(swell_water_heights(handle_.get(), t, xz.data(), xz.size(), out.data(), out.size()));
        return out;
    }

  private:
    std::unique_ptr<SwellWater, WaterDeleter> handle_;
    size_t rows_ = 0, cols_ = 0;
};

const char *SCENE = R"(version = 1
[camera]
eye = [0.0, 12.0, 60.0]
target = [0.0, 0.0, 0.0]
[render]
width = 96
height = 54
[water]
model = 'fft'
size = [64.0, 64.0]
cells = [32, 32]
grid = 32
patch_size = 64.0
wind_speed = 12.0
choppiness = 1.0
foam = true
seed = 3
)";

}  // namespace

int main() {
    try {
        Water water(SCENE);
        std::vector<float> positions, normals;
        const std::vector<float> buoy = {3.0f, -4.0f};
        for (int frame = 0; frame < 3; frame++) {
            double t = frame / 24.0 + 1.0;
            water.displace(t, positions, normals);
            float h = water.heights(t, buoy)[0];
            std::printf("t %.9g buoy %.9g vertex0 %.9g %.9g %.9g\n", t, h, positions[0], positions[1], positions[2]);
        }
        try {
            Water bad("version = 1\n[camera]\neye = [0.0, 1.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n"
                      "[water]\nmodel = 'fft'\ngrid = 100\n");
        } catch (const std::runtime_error &e) {
            std::printf("bad scene: %s\n", e.what());
        }
        SwellScene *raw = nullptr;
        check(swell_scene_from_toml(SCENE, &raw));
        std::unique_ptr<SwellScene, SceneDeleter> scene(raw);
        uint32_t width = 0, height = 0;
        check(swell_scene_image_size(scene.get(), &width, &height));
        std::vector<unsigned char> rgba(4u * width * height);
        check(swell_scene_render_rgba8(scene.get(), 1.0, rgba.data(), rgba.size()));
        unsigned long sum = 0;
        for (unsigned char b : rgba) sum += b;
        std::printf("rendered %ux%u, byte sum %lu\n", width, height, sum);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
