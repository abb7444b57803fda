// The IES LM-63 reader (ies_file.h). The numbers after the TILT line are a stream of tokens
// separated by blanks, line breaks or commas, whatever the lines; each keeps its line so an
// error names it. Every count is bounded before anything is allocated by it, and every value
// is checked as it is read, so a damaged file stops with one message and never a crash.
#include "light/ies_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace mirage {

namespace {

// Large enough for any real goniometer (1° steps over the full sphere are 181 × 361).
constexpr int kMaxAngles = 2000;

struct Token {
    std::string text;
    int line;
};

class TokenStream {
public:
    TokenStream(std::vector<Token> tokens, std::string name, int lastLine)
        : mTokens(std::move(tokens)), mName(std::move(name)), mLastLine(lastLine) {}

    [[noreturn]] void fail(int line, const std::string& what) const {
        throw MirageError(FileLoc{mName, line, 0}, what);
    }
    // The next token as a finite number; `what` says what it should be.
    double number(const std::string& what) {
        if (mNext >= mTokens.size())
            fail(mLastLine, "expected " + what + ", found the end of the file");
        const Token& t = mTokens[mNext++];
        errno = 0;
        char* end = nullptr;
        const double v = std::strtod(t.text.c_str(), &end);
        if (end == t.text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
            fail(t.line, "expected " + what + ", found '" + t.text.substr(0, 40) + "'");
        mLine = t.line;
        return v;
    }
    // A whole number in [lo, hi].
    int count(const std::string& what, int lo, int hi) {
        const std::string expected = what + " (a whole number from " + std::to_string(lo) + " to " +
                                     std::to_string(hi) + ")";
        const double v = number(expected);
        if (v != std::floor(v) || v < lo || v > hi)
            fail(mLine, "expected " + expected + ", found " + std::to_string(v));
        return int(v);
    }
    // A number ≥ lo (> lo when strict).
    double atLeast(const std::string& what, double lo, bool strict) {
        const double v = number(what);
        if (strict ? !(v > lo) : !(v >= lo))
            fail(mLine, "expected " + what + ", found " + std::to_string(v));
        return v;
    }
    // n angles in [lo, hi] degrees, strictly increasing.
    std::vector<float> angles(int n, const std::string& what, double lo, double hi) {
        std::vector<float> a;
        for (int i = 0; i < n; ++i) {
            const double v = number(what + " (degrees)");
            if (v < lo || v > hi || (i > 0 && !(v > a.back())))
                fail(mLine, "expected " + what + " increasing within " + std::to_string(int(lo)) +
                                "–" + std::to_string(int(hi)) + "°, found " + std::to_string(v));
            a.push_back(float(v));
        }
        return a;
    }
    int line() const { return mLine; }

private:
    std::vector<Token> mTokens;
    std::string mName;
    int mLastLine;
    size_t mNext = 0;
    int mLine = 0;
};

// Splits the text after the TILT line into tokens at blanks and commas.
std::vector<Token> tokenize(std::istringstream& in, int* line) {
    std::vector<Token> tokens;
    std::string text;
    while (std::getline(in, text)) {
        ++*line;
        std::replace(text.begin(), text.end(), ',', ' ');
        std::istringstream words(text);
        std::string word;
        while (words >> word) tokens.push_back(Token{word, *line});
    }
    return tokens;
}

// A tilt table (TILT=INCLUDE): lamp-to-luminaire geometry, the number of pairs, the angles and
// the multiplying factors. The profile is the one at the measured tilt, so the table is only
// checked.
void skipTilt(TokenStream& s) {
    s.count("the lamp-to-luminaire geometry of TILT=INCLUDE", 1, 3);
    const int pairs = s.count("the number of tilt angles", 1, kMaxAngles);
    s.angles(pairs, "tilt angles", 0.0, 180.0);
    for (int i = 0; i < pairs; ++i) s.atLeast("a tilt multiplying factor ≥ 0", 0.0, false);
}

}  // namespace

IesProfile IesProfile::parse(const std::string& text, const std::string& name) {
    std::istringstream in(text);
    std::string header;
    int line = 0;
    bool tilt = false;
    // Header lines (IESNA:LM-63-…, [KEYWORD] lines, or the free text of older files) up to TILT.
    while (!tilt && std::getline(in, header)) {
        ++line;
        const size_t start = header.find_first_not_of(" \t");
        tilt = start != std::string::npos && header.compare(start, 5, "TILT=") == 0;
        if (tilt) header = header.substr(start + 5);
    }
    if (!tilt) throw MirageError(FileLoc{name, line, 0}, "expected a 'TILT=' line (IES LM-63)");
    while (!header.empty() && std::isspace(static_cast<unsigned char>(header.back())))
        header.pop_back();
    const int tiltLine = line;
    if (header != "NONE" && header != "INCLUDE")
        throw MirageError(FileLoc{name, tiltLine, 0},
                          "expected TILT=NONE or TILT=INCLUDE (a tilt file of its own is not "
                          "read), found TILT=" +
                              header.substr(0, 40));
    std::vector<Token> tokens = tokenize(in, &line);  // counts the lines first: the last one
    TokenStream s(std::move(tokens), name, line);
    if (header == "INCLUDE") skipTilt(s);

    IesProfile p;
    s.count("the number of lamps", 1, 1000);
    s.number("the lumens per lamp");  // −1 for absolute photometry: the power is the scene's
    const double multiplier = s.atLeast("the candela multiplier (> 0)", 0.0, true);
    const int nv = s.count("the number of vertical angles", 2, kMaxAngles);
    const int nh = s.count("the number of horizontal angles", 1, kMaxAngles);
    if (s.count("the photometric type", 1, 3) != 1)
        s.fail(s.line(), "expected photometric type 1 (type C); types A and B are not read");
    s.count("the units type (1 feet, 2 metres)", 1, 2);
    for (const char* d : {"the luminous width", "the luminous length", "the luminous height"})
        s.number(d);
    const double ballast = s.atLeast("the ballast factor (> 0)", 0.0, true);
    s.number("the ballast-lamp photometric factor");  // "future use" in LM-63-2002
    s.number("the input watts");

    p.mVertical = s.angles(nv, "vertical angles", 0.0, 180.0);
    const float v0 = p.mVertical.front(), v1 = p.mVertical.back();
    if (!((v0 == 0.f || v0 == 90.f) && (v1 == 90.f || v1 == 180.f)))
        s.fail(s.line(), "expected vertical angles from 0 or 90 to 90 or 180 (type C)");
    p.mHorizontal = s.angles(nh, "horizontal angles", 0.0, 360.0);
    const float h0 = p.mHorizontal.front(), h1 = p.mHorizontal.back();
    if (!(h0 == 0.f && (h1 == 0.f || h1 == 90.f || h1 == 180.f || h1 == 360.f)))
        s.fail(s.line(), "expected horizontal angles from 0 to 0, 90, 180 or 360 (type C)");

    const float scale = float(multiplier * ballast);
    p.mCandela.reserve(size_t(nv) * size_t(nh));
    for (int i = 0; i < nv * nh; ++i) {
        const float c = float(s.atLeast("a candela value ≥ 0", 0.0, false)) * scale;
        if (!std::isfinite(c)) s.fail(s.line(), "expected a candela value within range");
        p.mCandela.push_back(c);
        p.mPeak = std::max(p.mPeak, c);
    }
    if (!(p.mPeak > 0.f))
        s.fail(s.line(), "expected some candela value above 0 (the luminaire is dark)");
    return p;
}

IesProfile IesProfile::read(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw MirageError("cannot open IES file '" + path + "'");
    std::ostringstream text;
    text << f.rdbuf();
    return parse(text.str(), path);
}

// C folded into the range the file covers: its symmetry (ies_file.h) makes the rest a mirror.
float IesProfile::foldHorizontal(float c) const {
    c = std::fmod(c, 360.f);
    if (c < 0.f) c += 360.f;
    const float last = mHorizontal.back();
    if (last <= 0.f) return 0.f;
    if (last <= 90.f) {
        if (c > 180.f) c = 360.f - c;
        return c > 90.f ? 180.f - c : c;
    }
    if (last <= 180.f) return c > 180.f ? 360.f - c : c;
    return c;
}

namespace {

// The interval of sorted `a` holding x, and x's fraction across it (clamped to the ends).
void bracket(const std::vector<float>& a, float x, size_t* i, float* f) {
    if (a.size() == 1 || x <= a.front()) {
        *i = 0;
        *f = 0.f;
        return;
    }
    if (x >= a.back()) {
        *i = a.size() - 2;
        *f = 1.f;
        return;
    }
    const size_t hi = size_t(std::upper_bound(a.begin(), a.end(), x) - a.begin());
    *i = hi - 1;
    *f = (x - a[*i]) / (a[hi] - a[*i]);
}

}  // namespace

float IesProfile::candela(float gammaDeg, float cDeg) const {
    if (!(gammaDeg >= mVertical.front() && gammaDeg <= mVertical.back())) return 0.f;
    size_t iv, ih;
    float fv, fh;
    bracket(mVertical, gammaDeg, &iv, &fv);
    bracket(mHorizontal, foldHorizontal(cDeg), &ih, &fh);
    const size_t nv = mVertical.size();
    const size_t iv1 = std::min(iv + 1, nv - 1), ih1 = std::min(ih + 1, mHorizontal.size() - 1);
    auto at = [&](size_t h, size_t v) { return mCandela[h * nv + v]; };
    const float lo = at(ih, iv) + fv * (at(ih, iv1) - at(ih, iv));
    const float hi = at(ih1, iv) + fv * (at(ih1, iv1) - at(ih1, iv));
    return lo + fh * (hi - lo);
}

}  // namespace mirage
