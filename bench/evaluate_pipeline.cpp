// evaluate_pipeline: runs slice | smooth | fitspline (through the stream text, as the
// tools do) on generated blades and prints, per section, the fitted curve's distance to
// the exact profile. Usage: evaluate_pipeline [seeds] [misregistration_mm]
#include "section/bspline.h"
#include "section/fit_spline.h"
#include "section/generate.h"
#include "section/pipe.h"
#include "section/slice.h"
#include "section/smooth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

using namespace section;

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 1;
  const double misregistration = argc > 2 ? std::atof(argv[2]) : 0.0;
  try {
    std::printf("%-10s %4s %3s %6s %9s %9s %9s %9s %7s\n", "blade", "seed", "sec", "z", "rms_um", "max_um",
                "maxgap_um", "p95_um", "ms/sec");
    double worst_rms = 0, worst_max = 0;
    for (const char* kind : {"turbine", "compressor"}) {
      const BladeDesign blade = std::string(kind) == "turbine" ? turbine_blade() : compressor_blade();
      for (int seed = 1; seed <= seeds; ++seed) {
        std::vector<double> zs;
        for (int k = 1; k <= 9; ++k) zs.push_back(blade.span * k / 10.0);
        ScanOptions so;
        so.noise = 0.005;
        so.holes = 5;
        so.density_min = 0.25;
        so.outlier_fraction = 0.0002;
        so.misregistration = misregistration;
        so.seed = static_cast<std::uint64_t>(seed);
        // Scan only bands around the planes: the same data in the slabs, far fewer points.
        Cloud cloud;
        for (double z : zs) {
          so.z_min = z - 0.5;
          so.z_max = z + 0.5;
          so.seed = static_cast<std::uint64_t>(seed * 100 + int(z));
          const Scan s = generate_scan(blade, so);
          cloud.points.insert(cloud.points.end(), s.cloud.points.begin(), s.cloud.points.end());
        }
        const auto t0 = std::chrono::steady_clock::now();
        SliceOptions sopt;
        sopt.slab = 0.08;
        Stream stream = parse_stream(format_stream(to_stream(slice(cloud, planes_at({0, 0, 1}, zs), sopt), "slice")), "slice");
        smooth_stream(stream);
        stream = parse_stream(format_stream(stream), "smooth");
        fit_spline_stream(stream);
        stream = parse_stream(format_stream(stream), "fitspline");
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / zs.size();
        const auto curves = splines(stream);
        const Table& pts = stream.get("points", "slice");
        for (std::size_t k = 0; k < zs.size(); ++k) {
          const int id = static_cast<int>(k);
          const auto it = curves.find({id, 0});
          if (it == curves.end()) {
            std::printf("%-10s %4d %3d %6.1f   FAILED\n", kind, seed, id, zs[k]);
            continue;
          }
          std::vector<Eigen::Vector2d> measured;
          for (std::size_t r = 0; r < pts.rows(); ++r)
            if (int(pts.at(r, 0)) == id && int(pts.at(r, 1)) == 0) measured.emplace_back(pts.at(r, 3), pts.at(r, 4));
          const SectionTruth truth = section_truth(blade.at(zs[k]));
          const auto samples = sample(it->second, 20000);
          std::vector<double> d, dgap;
          double sum = 0, mx = 0, mxgap = 0;
          for (const auto& p : samples) {
            const double e = locate(truth, p).distance;
            double near = INFINITY;
            for (const auto& m : measured) near = std::min(near, (m - p).squaredNorm());
            sum += e * e;
            d.push_back(e);
            if (near <= 0.09) mx = std::max(mx, e);
            else mxgap = std::max(mxgap, e);
          }
          std::sort(d.begin(), d.end());
          const double rms = std::sqrt(sum / samples.size());
          worst_rms = std::max(worst_rms, rms);
          worst_max = std::max(worst_max, mx);
          std::printf("%-10s %4d %3d %6.1f %9.2f %9.2f %9.2f %9.2f %7.0f\n", kind, seed, id, zs[k], rms * 1e3, mx * 1e3,
                      mxgap * 1e3, d[d.size() * 95 / 100] * 1e3, ms);
        }
      }
    }
    std::printf("worst: rms %.2f um, max (measured within 0.3 mm) %.2f um\n", worst_rms * 1e3, worst_max * 1e3);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evaluate_pipeline: error: %s\n", e.what());
    return 1;
  }
}
