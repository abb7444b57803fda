// Photometric data of a luminaire in the IES LM-63 text format (ANSI/IESNA LM-63-1995 and
// LM-63-2002): the header's keyword lines, TILT=NONE or TILT=INCLUDE, then numbers — lamps,
// lumens per lamp, candela multiplier, the counts of vertical and horizontal angles, the
// photometric type, units and luminous dimensions, ballast factor, a reserved factor, input
// watts, the vertical angles, the horizontal angles, and the candela values (for each
// horizontal angle, one per vertical angle).
//
// Only type C photometry (photometric type 1, the goniometer of almost every file in use) is
// read: the vertical angle γ is measured from the nadir, the luminaire's axis (0°) to the
// zenith (180°); the horizontal angle C turns about that axis. A file may cover γ over 0–90,
// 90–180 or 0–180 (nothing is sent outside its range), and C over one value (rotationally
// symmetric), 0–90 (symmetric in each quadrant), 0–180 (symmetric about the 0–180 plane) or
// 0–360. A tilt table (TILT=INCLUDE) describes how the output changes as the lamp is tilted
// in its fixture; it is read and checked, and the profile is the one at the measured tilt.
#pragma once

#include <string>
#include <vector>

namespace mirage {

class IesProfile {
public:
    // Candela at vertical angle γ and horizontal angle C (degrees; C any value, folded by the
    // file's symmetry), bilinear between the file's angles; 0 outside its vertical range.
    float candela(float gammaDeg, float cDeg) const;
    // The largest candela value in the file (> 0).
    float peak() const { return mPeak; }
    int verticalCount() const { return int(mVertical.size()); }
    int horizontalCount() const { return int(mHorizontal.size()); }

    // Parses LM-63 text. `name` is what errors call the file. Throws MirageError
    // "name:line: expected …" on anything malformed; never reads past the text.
    static IesProfile parse(const std::string& text, const std::string& name);
    // Reads and parses a file; a missing or unreadable file is a MirageError naming it.
    static IesProfile read(const std::string& path);

private:
    std::vector<float> mVertical, mHorizontal;  // degrees, increasing
    std::vector<float> mCandela;                // [horizontal][vertical], times the multiplier
    float mPeak = 0.f;
    float foldHorizontal(float cDeg) const;
};

}  // namespace mirage
