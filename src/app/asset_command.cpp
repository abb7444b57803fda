#include <cstdio>

#include "app/commands.h"
#include "volume/asset_writer.h"

namespace mirage {

int runMakeAsset(const AssetOptions& o) {
    writeProceduralAsset(o.kind, o.output, o.resolution, o.seed);
    std::printf("wrote %s (%s, resolution %d, seed %llu)\n", o.output.c_str(), o.kind.c_str(),
                o.resolution, (unsigned long long)o.seed);
    return 0;
}

}  // namespace mirage
