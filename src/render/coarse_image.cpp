// The coarse image (coarse_image.h).
#include "render/coarse_image.h"

#include "core/error.h"
#include "film/film_resample.h"

namespace mirage {

bool coarseImagePossible(const RenderSettings& s) { return s.region.empty() && s.aovs.empty(); }

RenderSettings coarseSettings(const RenderSettings& frame) {
    RenderSettings s = frame;
    s.width = (frame.width + kCoarseDivisor - 1) / kCoarseDivisor;
    s.height = (frame.height + kCoarseDivisor - 1) / kCoarseDivisor;
    s.region = {};
    s.aovs.clear();
    s.deep = {};
    s.progress = Progress::Mode::Quiet;
    return s;
}

CoarseImage::CoarseImage(const RenderSettings& frame)
    : film(coarseSettings(frame).width, coarseSettings(frame).height) {}

bool addCoarseSamples(const RenderScene& scene, Integrator& integrator, const RenderSettings& frame,
                      int spp, CoarseImage* image) {
    MIRAGE_CHECK(spp >= 1 && coarseImagePossible(frame));
    RenderSettings s = coarseSettings(frame);
    s.spp = spp;
    TileCheckpoint from;
    from.initial = &image->film;
    from.cancel = image->cancel;
    RenderStats stats;
    Film next = render(scene, integrator, s, &stats, &from, PassSamples{image->spp, nullptr});
    if (stats.interrupted) return false;
    image->film = std::move(next);
    image->spp += spp;
    return true;
}

Film magnifyCoarse(const CoarseImage& image, const RenderSettings& frame) {
    return magnify(image.film, frame.width, frame.height);
}

}  // namespace mirage
