// Where in its box a medium exists: everywhere, or only inside a closed region (the interior of
// a closed shape, `interior_medium` in a scene file), less the closed regions cut out of it (the
// inside of shapes that hold other media: a glass sphere of ink in fog, water in a tank). Every
// coefficient is zero elsewhere. The medium owns one (Medium::setConfinement) and tests its
// lookups against it; tracking and the optical-depth march clip rays with it. The regions are
// the core/region.h interface, so medium/ knows nothing of the surfaces that implement them.
//
// The majorant grid stays a valid upper bound of a confined medium, so null-collision tracking
// needs no change; a homogeneous medium keeps its closed-form transmittance while every ray
// meets it in one interval (oneInterval()).
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/region.h"

namespace mirage {

class Confinement {
public:
    // The medium exists only inside `region` (replacing any region given before).
    void confineTo(std::shared_ptr<const Region> region) { mRegion = std::move(region); }
    // The medium does not exist inside `region` (null: nothing is cut out).
    void excludeFrom(std::shared_ptr<const Region> region) {
        if (region) mExcluded.push_back(std::move(region));
    }

    // Null: the whole box.
    const Region* region() const { return mRegion.get(); }
    const std::vector<std::shared_ptr<const Region>>& excluded() const { return mExcluded; }
    // False when neither a region nor a cut-out applies: every point of the box is inside.
    bool confines() const { return mRegion || !mExcluded.empty(); }
    // Any straight ray's part inside is one interval of its part inside the box: no region or a
    // convex one, and nothing cut out.
    bool oneInterval() const { return (!mRegion || mRegion->convex()) && mExcluded.empty(); }

    // False for a world point outside the region or inside one cut out of it.
    bool contains(const Vec3& pWorld) const {
        if (mRegion && !mRegion->contains(pWorld)) return false;
        for (const auto& r : mExcluded)
            if (r->contains(pWorld)) return false;
        return true;
    }
    // Narrows [*t0, *t1] (world ray parameters) to the region's chord, or to its first entry and
    // last exit where it is not convex (Region::clip); false when the ray misses it there.
    // Cut-outs are not clipped: contains() decides within the span.
    bool clip(const Ray& worldRay, float* t0, float* t1) const {
        return !mRegion || mRegion->clip(worldRay, t0, t1);
    }
    // World bounds shrunk to the region's (empty when the two do not overlap).
    Bounds3 clipBounds(Bounds3 worldBounds) const {
        if (!mRegion) return worldBounds;
        const Bounds3 r = mRegion->bounds();
        worldBounds.lo = vmax(worldBounds.lo, r.lo);
        worldBounds.hi = vmin(worldBounds.hi, r.hi);
        return worldBounds;
    }

private:
    std::shared_ptr<const Region> mRegion;
    std::vector<std::shared_ptr<const Region>> mExcluded;
};

}  // namespace mirage
