// Hot loops compiled twice, for AVX2 and for baseline x86-64, the variant picked when the program
// loads (function multiversioning). AVX2 without FMA performs the same IEEE operations in the same
// order, so both variants give the same bits; AVX2 only brings three-operand encoding (fewer
// register copies) and wider vectors. Elsewhere, or with FNET_SIM_NO_CLONES, one plain version.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(FNET_SIM_NO_CLONES)
#define FNET_SIM_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define FNET_SIM_CLONES
#endif
