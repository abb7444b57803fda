// Every Embree BVH build in Mirage (surfaces, mesh interiors, photon discs) goes through
// commitEmbreeScene, so that one place knows how the build runs under ThreadSanitizer.
#pragma once

#include <embree3/rtcore.h>

namespace mirage {

// rtcCommitScene(scene). In a ThreadSanitizer build only, the BVH build runs on the calling
// thread alone (see embree_commit.cpp for why); everywhere else it uses all of TBB's threads.
void commitEmbreeScene(RTCScene scene);

}  // namespace mirage
