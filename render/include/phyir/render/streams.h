#pragma once
// Every random stream of the renderer, named in one place. Images are bit-identical for a
// seed whatever the thread count because every random number comes from a stream keyed by
// what it is for (a Purpose) and by the sample it belongs to, never from a shared
// generator. A new estimator adds its purposes here; nothing else derives streams.
//
// Keys. sample_key(seed, item, sample) is the key of one sample of one item (a pixel, a
// probe texel, a cache cell). stream_key(key, purpose, index) derives from it the key of
// one purpose's stream, `index` numbering repeats of that purpose within the sample (the
// bounce of a path, the specular depth of a probe texel, the first sample id of a batch);
// stream(key, purpose, index) is the generator seeded with it and numbered by the purpose.
#include <cstdint>

#include "phyir/render/rng.h"

namespace phyir::render {

// The values are part of the output: renumbering a purpose changes every image rendered
// with it.
enum class Purpose : uint64_t {
  // The path tracer, per bounce.
  kPathBrdf = 1,         // BRDF sample continuing the path
  kPathLight = 2,        // next-event estimation on the emitters
  kPathEnvironment = 3,  // next-event estimation on the environment
  kPathRoulette = 4,     // Russian roulette
  kPathGlass = 5,        // lobe choice and direction at glass
  kPathPortal = 6,       // next-event estimation on the environment through the light portals
  kPathGuide = 7,        // path guiding: the choice between the BRDF and the guide (guide_mixture.h)
  kPathLightSubpath = 8, // the light subpath joined at a vertex (light_subpaths.h)
  // The radiance cache, per estimate.
  kCacheFallbackDirection = 102,  // a lookup outside every cell
  kCacheFillDirections = 103,     // permutation of a cache point's stratified cosine directions
  kCacheFillLight = 104,          // the light choice of a fill estimate
  kCacheFillLightPoints = 105,    // permutation of a cache point's stratified light points
  kCachePoint = 106,              // per item (cell), index = the cell's point: its fill's key
  kCacheFillEnvironment = 107,    // the environment sample of a fill estimate
  kCacheFillPortal = 108,         // its sample through the light portals
  kCacheFillLightSubpath = 109,   // the light subpath joined at a fill estimate's point
  // The probe texel estimator, per specular depth.
  kTexelLight = 201,              // a next-event sample
  kTexelBrdf = 202,               // the BRDF- or GGX-sampled ray
  kTexelLookup = 203,             // key of a cache lookup (its fallback's stream)
  kTexelGlass = 204,              // key of the path traced through glass
  kTexelSpecularRoulette = 205,   // whether the specular ray is followed
  kTexelLightRepeat = 206,        // key of the k-th light sample of a multi-sample estimate
  kTexelChainEnd = 207,           // whether a specular chain's end is path traced (progressive passes)
  kTexelChainEndPath = 208,       // key of that path
  // The probe renderer, per texel; `index` is the first sample id of a batch.
  kProbeDiscovery = 301,    // the ray that offers the texel's first hit to the cache
  kProbeStrata = 302,       // permutation of a batch's strata
  kProbeInterleave = 303,   // the strata interleaving shared by neighbouring probes (per texel)
  kProbeLightPart = 304,    // directions inside the lights' coverage of a texel
  kProbeCacheTieBreak = 305,  // which discovered points a cache cell keeps
  kProbePhoton = 306,          // the jitter of a punctual light's photon directions
  kProbePhotonRoulette = 307,  // which photons a probe joins, where many land in a texel
  // Pixels: the scrambling of a pixel's stratified first-bounce samples.
  kPixelScramble = 401,
  kPixelLightSelect = 402,
  kPixelLightPoint = 403,
  kPixelLobe = 404,
  kPixelBrdf = 405,
  // Seeds of a view's parts, from the render seed.
  kProbeSeed = 501,
  kCacheSeed = 502,
  kProbeRefinePass = 503,  // per pass: the seed of a pass towards the error target
};

// The key of sample `sample` of item `item` (a pixel, a probe texel, a cache cell).
inline uint64_t sample_key(uint64_t seed, uint64_t item, uint64_t sample) {
  return mix64(mix64(seed) ^ mix64(item * 0x100000001B3ull + sample));
}

// Every derivation is this one: a purpose's streams never meet another's (purposes sit in
// the top 24 bits, indices below 2^40) and mix64 decorrelates neighbouring keys.
inline uint64_t stream_key(uint64_t key, Purpose purpose, uint64_t index = 0) {
  return mix64(key ^ mix64((uint64_t(purpose) << 40) + index));
}

// The generator of a stream whose key is already derived (stream_key, item_stream_key).
inline Rng generator(uint64_t stream_key, Purpose purpose) { return Rng(stream_key, uint64_t(purpose)); }

// The generator of that stream.
inline Rng stream(uint64_t key, Purpose purpose, uint64_t index = 0) {
  return generator(stream_key(key, purpose, index), purpose);
}

// The key of `purpose`'s stream number `index` of a whole item (not of one of its samples):
// a probe texel's discovery ray, its strata permutations, its lights' coverage directions,
// a cache cell's points. Derived from the item's first sample key, with purposes no sample
// uses.
inline uint64_t item_stream_key(uint64_t seed, uint64_t item, Purpose purpose, uint64_t index = 0) {
  return stream_key(sample_key(seed, item, 0), purpose, index);
}

// The generator of that stream.
inline Rng item_stream(uint64_t seed, uint64_t item, Purpose purpose, uint64_t index = 0) {
  return generator(item_stream_key(seed, item, purpose, index), purpose);
}

}  // namespace phyir::render
