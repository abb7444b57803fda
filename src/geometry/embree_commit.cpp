#include "geometry/embree_commit.h"

#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define MIRAGE_UNDER_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define MIRAGE_UNDER_TSAN 1
#endif

#ifdef MIRAGE_UNDER_TSAN
#include <tbb/task_arena.h>
#endif

namespace mirage {

void commitEmbreeScene(RTCScene scene) {
#ifdef MIRAGE_UNDER_TSAN
    // Embree builds its BVH with TBB tasks whose code (oneTBB's header templates: task
    // construction, completion, the wait context) is compiled into libembree3.so, which is not
    // instrumented. Even against a TSan-built libtbb, the release that ends each of those tasks
    // is invisible, so TSan reports the build's own memory (freed and moved by Embree) and the
    // stack slots of Embree's task_group_context, reused afterwards by Mirage, as races between
    // the build's threads and the caller. None of that memory is Mirage's, and Embree's own
    // loads and stores are invisible to TSan anyway. An arena of one slot keeps every task of
    // the build on this thread, so those reports cannot arise, while Mirage's ray queries and
    // its Embree callbacks (run on Mirage's render threads) stay checked.
    tbb::task_arena oneThread(1);
    oneThread.execute([scene] { rtcCommitScene(scene); });
#else
    rtcCommitScene(scene);
#endif
}

}  // namespace mirage
