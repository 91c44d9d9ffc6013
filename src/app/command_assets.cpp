// haif assets: (re)writes the generated mesh assets (assets/README.md lists them).
#include "app/cli.h"
#include "app/commands.h"
#include "scene/asset_catalog.h"
#include "tools/interrupts.h"

#include <cstdio>

namespace haif {

int commandAssets(int argc, char** argv) {
  CommandLine cl("assets", {"--out"}, {});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  if (!cl.positional().empty()) {
    std::fprintf(stderr, "haif assets: unexpected argument '%s' (see 'haif help')\n", cl.positional()[0].c_str());
    return 2;
  }
  const std::string dir = cl.get("--out", "assets");
  // The assets are staged in DIR/.assets.tmp and moved in one by one once all are written.
  registerTemporary(dir + "/.assets.tmp");
  if (!writeGeneratedAssets(dir, error)) {
    waitIfInterrupted();
    std::fprintf(stderr, "haif assets: %s\n", error.c_str());
    return 1;
  }
  for (const GeneratedAsset& a : generatedAssets())
    std::printf("%s/%s: %zu vertices, %zu triangles\n", dir.c_str(), a.file.c_str(), a.mesh.vertices.size(),
                a.mesh.indices.size() / 3);
  return 0;
}

}  // namespace haif
