// `mirage make-asset`: a procedural VDB cache (tools/asset_writer.h) written to a file.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "tools/asset_writer.h"
#include "tools/tools.h"

namespace mirage {

int runMakeAsset(const AssetOptions& o) {
    const int resolution =
        o.voxels > 0 ? assetResolutionForVoxels(o.kind, o.seed, o.voxels) : o.resolution;
    writeProceduralAsset(o.kind, o.output, resolution, o.seed, !o.quiet);
    std::printf("wrote %s (%s, resolution %d, seed %llu)\n", o.output.c_str(), o.kind.c_str(),
                resolution, (unsigned long long)o.seed);
    return 0;
}

Command addMakeAssetCommand(CLI::App& app) {
    auto o = std::make_shared<AssetOptions>();
    auto* asset = app.add_subcommand("make-asset", "Write a procedural VDB cache");
    asset->add_option("kind", o->kind,
                      "smoke | smoke-sphere | fire | plume | fog-sphere | ocean | pyro")
        ->required();
    asset->add_option("-o,--output", o->output, "Output .vdb (written atomically)")->required();
    auto* resolution = asset->add_option("--resolution", o->resolution,
                                         "Voxels along the 2 m height, 8 to 4096 (default 64)");
    resolution->check(CLI::Range(kMinAssetResolution, kMaxAssetResolution));
    asset
        ->add_option("--voxels", o->voxels,
                     "Aim at this many active voxels in the first grid (e.g. 1e9): picks the "
                     "resolution")
        ->check(CLI::PositiveNumber)
        ->excludes(resolution);
    asset->add_flag("--quiet", o->quiet, "No progress bar");
    asset->add_option("--seed", o->seed, "Noise seed (default 1; fog-sphere ignores it)");
    return {asset, [o] { return runMakeAsset(*o); }};
}

}  // namespace mirage
