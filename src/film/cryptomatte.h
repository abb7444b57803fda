// Cryptomatte (Friedman & Jones 2015, "Fully Automatic ID Mattes with Support for Motion Blur
// and Transparency", and Psyop's Cryptomatte specification v1.2): per pixel, the objects seen
// and the share of the pixel's coverage each contributes, as ID mattes a compositor picks by
// name (Nuke's Cryptomatte gizmo).
//
// An object's ID is MurmurHash3_x86_32 of its name (seed 0), as a float32 whose bits are the
// hash, with the exponent moved off 0 and 255 so that no ID is a denormal, an infinity or a NaN.
// A Cryptomatte of type `crypto_volume` is written as the layers crypto_volume00, 01, 02, each
// R G B A holding two ranks (ID, coverage), the objects in decreasing order of coverage: six
// ranks. The header carries, under the key made of the first 7 hex digits of the hash of the
// type's name, its name, the hash and conversion used, and the manifest {name: hex hash}.
//
// Coverage (render/camera_ray_data.h): along the camera ray, the opacity each medium adds where
// it is met (T σt dt, by ratio tracking) and the transmittance left at the first opaque surface,
// scaled per sample to the beauty's own alpha; the film averages it over the pixel's samples,
// so the coverages of a pixel's objects sum to its alpha.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "film/film.h"

namespace mirage {

// MurmurHash3_x86_32 (Appleby's public-domain MurmurHash3, the 32-bit x86 variant) of `key`.
uint32_t murmurHash3_32(const std::string& key, uint32_t seed = 0);

// The ID of a hash as the specification stores it: the float32 with the hash's bits, the lowest
// exponent bit flipped where the exponent is 0 (denormal, zero) or 255 (infinity, NaN).
float cryptomatteId(uint32_t hash);

// The ranks a Cryptomatte keeps per pixel (the specification's default), two per layer.
constexpr int kCryptomatteRanks = 6;

// The layers <type>00, 01, 02 of one Cryptomatte, from each pixel's mean coverage per object:
// coverage[p * objects.size() + i] is object i's mean coverage in pixel p. Objects of equal
// names share an ID, and their coverages are added.
std::vector<ImageLayer> cryptomatteLayers(const std::string& type,
                                          const std::vector<std::string>& objects,
                                          const std::vector<float>& coverage, size_t pixels);

// The header attributes cryptomatte/<key>/name, hash, conversion and manifest of one type.
std::vector<std::pair<std::string, std::string>> cryptomatteAttributes(
    const std::string& type, const std::vector<std::string>& objects);

// Whether `name` may name an object in a Cryptomatte: letters, digits and _ - . / : (so that
// it needs no escaping in the manifest's JSON nor in the partial file's lists).
bool validCryptomatteName(const std::string& name);

}  // namespace mirage
