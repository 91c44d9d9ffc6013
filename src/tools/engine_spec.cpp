#include "tools/engine_spec.h"

#include "tools/haif_engine_run.h"
#ifdef HAIF_HAVE_BULLET
#include "tools/bullet_engine_run.h"
#endif

namespace haif {

bool parseEngineSpec(const std::string& text, EngineSpec& out, std::string& error) {
  const size_t colon = text.find(':');
  const std::string head = text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  EngineSpec s;
  if (head == "bullet") {
    s.engine = "bullet";
    s.solver.mode = "fixed";
    if (rest.empty()) {  // the scene's iteration count
      out = s;
      return true;
    }
    const std::string counts = rest.rfind("fixed:", 0) == 0 ? rest : "fixed:" + rest;
    if (!parseSolverSpec(counts, s.solver, error) || s.solver.mode != "fixed") {
      error = "engine spec '" + text + "': Bullet runs fixed iteration counts only, e.g. bullet:10";
      return false;
    }
    out = s;
    return true;
  }
  if (head == "haif" && rest.empty()) {  // fixed, the scene's iteration count
    out = s;
    return true;
  }
  const std::string solver = head == "haif" ? rest : text;
  if (!parseSolverSpec(solver, s.solver, error)) {
    error = "engine spec '" + text + "': " + error + " (engines: haif, bullet)";
    return false;
  }
  out = s;
  return true;
}

bool bulletAvailable() {
#ifdef HAIF_HAVE_BULLET
  return true;
#else
  return false;
#endif
}

std::unique_ptr<EngineRun> makeEngineRun(const EngineSpec& spec, const std::string& scenePath, int threads,
                                         std::string& error) {
  if (spec.engine == "haif") return HaifEngineRun::create(scenePath, spec.solver, threads, error);
  if (spec.engine == "bullet") {
#ifdef HAIF_HAVE_BULLET
    return BulletEngineRun::create(scenePath, spec.solver.iterations, error);
#else
    error = "engine 'bullet': this haif was built without Bullet (install libbullet-dev, then re-run cmake)";
    return nullptr;
#endif
  }
  error = "unknown engine '" + spec.engine + "' (haif, bullet)";
  return nullptr;
}

}  // namespace haif
