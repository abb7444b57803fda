// Light groups of the photon estimates (docs/aovs.md): every photon carries the light it left
// (Photon::light), and an estimate that is asked for its groups adds each photon's term to its
// light's group as well as to its total. The groups of an estimate therefore sum to it, up to
// float rounding, and the light-group passes of the photon integrator sum to the beauty like
// those of the path tracers. Light emitted by a medium (fire) is in the emission group, slot 0,
// whichever light it later met: it is light of the medium, scattered.
#pragma once

#include <vector>

#include "core/math.h"
#include "photon/photon.h"

namespace mirage {

class PhotonGroups {
public:
    // Inactive: add() does nothing (a render without light-group passes).
    PhotonGroups() = default;
    // `slotOfLight[i]` is light i's group slot (film/aov.h: 0 emission, g + 1 group g); the
    // estimate's parts go to sums[slot], which has a slot for every group.
    PhotonGroups(const std::vector<int>* slotOfLight, std::vector<Vec3>* sums)
        : mSlotOfLight(slotOfLight), mSums(sums) {}

    bool active() const { return mSums != nullptr; }
    void add(const Photon& p, const Vec3& term) const {
        if (mSums) (*mSums)[slot(p)] += term * mFactor;
    }
    // The same sums, each term multiplied by s too: a factor an estimate applies to the sum of
    // all its photons (a kernel's normalisation, a march's step).
    PhotonGroups scaled(float s) const {
        PhotonGroups g = *this;
        g.mFactor *= s;
        return g;
    }

private:
    size_t slot(const Photon& p) const {
        return p.light == Photon::kFromMedium ? 0 : size_t((*mSlotOfLight)[p.light]);
    }

    const std::vector<int>* mSlotOfLight = nullptr;
    std::vector<Vec3>* mSums = nullptr;
    float mFactor = 1.f;
};

}  // namespace mirage
