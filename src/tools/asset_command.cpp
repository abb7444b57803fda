// `mirage make-asset`: a procedural VDB cache (tools/asset_writer.h) written to a file.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

#include "tools/asset_writer.h"
#include "tools/tools.h"

namespace mirage {

int runMakeAsset(const AssetOptions& o) {
    writeProceduralAsset(o.kind, o.output, o.resolution, o.seed);
    std::printf("wrote %s (%s, resolution %d, seed %llu)\n", o.output.c_str(), o.kind.c_str(),
                o.resolution, (unsigned long long)o.seed);
    return 0;
}

Command addMakeAssetCommand(CLI::App& app) {
    auto o = std::make_shared<AssetOptions>();
    auto* asset = app.add_subcommand("make-asset", "Write a procedural VDB cache");
    asset->add_option("kind", o->kind, "smoke | fire | fog-sphere | ocean")->required();
    asset->add_option("-o,--output", o->output, "Output .vdb (written atomically)")->required();
    asset->add_option("--resolution", o->resolution, "Voxels along the 2 m height, 8 to 1024 "
                                                     "(default 64)")
        ->check(CLI::Range(8, 1024));
    asset->add_option("--seed", o->seed, "Noise seed (default 1; fog-sphere ignores it)");
    return {asset, [o] { return runMakeAsset(*o); }};
}

}  // namespace mirage
