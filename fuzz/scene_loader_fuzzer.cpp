// libFuzzer target for the scene loader: any byte string must either load into a
// valid Scene or be refused with an InputError — never crash, hang, leak, or throw
// anything else. Built with -DRIGIDITY_BUILD_FUZZERS=ON (clang), run by scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rigidity/errors.hpp"
#include "rigidity/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // A scene may list plugins, which the loader dlopen()s: the fuzzer must not load
  // arbitrary libraries of this machine, so such inputs are not run.
  if (text.find("plugins") != std::string_view::npos || text.find("plug") != std::string_view::npos) return 0;
  try {
    const rigidity::Scene scene = rigidity::load_scene_string(text, "<fuzz>");
    // What the loader promises the solvers (scene.hpp): checked again here.
    if (scene.bodies.empty() || !(scene.t_end > 0.0) || !std::isfinite(scene.t_end)) std::abort();
    double previous_right = -INFINITY;
    for (const rigidity::BodyDecl& body : scene.bodies) {
      if (body.segments.empty() || !(body.position >= previous_right)) std::abort();
      double x = body.position;
      for (const rigidity::Segment& seg : body.segments) {
        if (!(seg.length > 0.0) || !std::isfinite(seg.rapidity)) std::abort();
        if (!scene.material_of(seg).admissibility_violation(seg.stretch).empty()) std::abort();
        x += seg.length * seg.stretch.value() / std::cosh(seg.rapidity);
      }
      previous_right = x;
    }
  } catch (const rigidity::InputError&) {
    // refused with a located message: fine
  }
  return 0;
}
