/**
 * @file
 * The vector instructions of the explicit loop's batches (node_update.cc,
 * joints.cc): as many triangles or joints per batch as one register holds
 * doubles, one per lane of a GCC vector, compiled once per instruction set
 * and chosen at run time. Every lane does the operations of the
 * element-by-element loop in the same order, so the results are bitwise the
 * same whichever is chosen (tests/discrete/vector_instructions.py).
 */
#ifndef tmfdem_discrete_vector_instructions_h
#define tmfdem_discrete_vector_instructions_h

#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /** Instruction set of the batches of the explicit loop. */
    enum class VectorInstructions
    {
      none,   ///< element by element (no batches)
      sse2,   ///< 128-bit registers (every x86-64 processor)
      avx2,   ///< 256-bit registers
      avx512, ///< 512-bit registers (AVX-512F)
    };

    /**
     * Triangles or joints per batch with @p instructions: one vector
     * register of doubles (AVX-512 8, AVX2 4, SSE2 2), 0 with none.
     */
    constexpr unsigned int
    vector_lanes(const VectorInstructions instructions)
    {
      return instructions == VectorInstructions::avx512 ? 8 :
             instructions == VectorInstructions::avx2   ? 4 :
             instructions == VectorInstructions::sse2   ? 2 :
                                                          0;
    }

    /** The most lanes of any instruction set. */
    constexpr unsigned int max_vector_lanes = 8;

    /** A vector of @p lanes doubles (GCC vector extension; type) and the
     *  result of comparing two (mask: all bits set where true). */
    template <unsigned int lanes>
    struct LaneVector
    {
      typedef double type __attribute__((vector_size(lanes * sizeof(double))));
      typedef long long mask
        __attribute__((vector_size(lanes * sizeof(double))));
    };

    /**
     * @name Lane by lane
     * What a kernel written once for double and for the lane vectors
     * (element_kernel.h, joint_kernel.h) needs beyond the arithmetic
     * operators and the ternary `mask ? a : b`, which GCC's vector
     * extension provides for both: the same call on a double and on a
     * vector, the vector version doing per lane what the double version
     * does, so that both round alike. Idioms of such kernels: `Number
     * zero{}` and `zero + 1.` make a zero and a one of either type (a
     * double, or one in every lane); `decltype(Number() > 1.)` is the type
     * of a comparison (bool, or a lane mask: all bits set where true);
     * `a & b` and `a | b` of two comparisons are an int for doubles and a
     * mask for vectors, and either selects in `cond ? x : y`.
     */
    ///@{
    /** Is the comparison @p b true (a double's comparison)? */
    __attribute__((always_inline)) inline bool
    any_lane(const bool b)
    {
      return b;
    }

    /** Is the comparison @p mask true in some lane? (The lanes or-ed
     *  together, no branch per lane.) */
    template <typename Mask,
              typename = std::enable_if_t<!std::is_arithmetic_v<Mask>>>
    __attribute__((always_inline)) inline bool
    any_lane(const Mask mask)
    {
      auto bits = mask[0];
      for (unsigned int l = 1; l < sizeof(Mask) / sizeof(mask[0]); ++l)
        bits |= mask[l];
      return bits != 0;
    }

    /** @p f applied to each lane of @p v (to @p v itself for a double). */
    template <typename Number, typename Function>
    __attribute__((always_inline)) inline Number
    lane_map(const Function &f, const Number v)
    {
      if constexpr (std::is_arithmetic_v<Number>)
        return f(v);
      else
        {
          Number r = v;
          for (unsigned int l = 0; l < sizeof(Number) / sizeof(double); ++l)
            r[l] = f(v[l]);
          return r;
        }
    }

    /** The square root, lane by lane. */
    template <typename Number>
    __attribute__((always_inline)) inline Number
    lane_sqrt(const Number v)
    {
      return lane_map([](const double a) { return std::sqrt(a); }, v);
    }

    /** |v|, lane by lane (the sign bit cleared, as std::abs does). */
    template <typename Number>
    __attribute__((always_inline)) inline Number
    lane_abs(const Number v)
    {
      if constexpr (std::is_arithmetic_v<Number>)
        return std::abs(v);
      else
        {
          using Mask = decltype(v < v);
          return reinterpret_cast<Number>(reinterpret_cast<Mask>(v) &
                                          0x7fffffffffffffffLL);
        }
    }

    /** The larger of @p a and @p b, lane by lane, as std::max picks it. */
    template <typename Number>
    __attribute__((always_inline)) inline Number
    lane_max(const Number a, const Number b)
    {
      return a < b ? b : a;
    }
    ///@}

    /** Names of the instruction sets (prm entry Discrete
     *  mechanics/Vector instructions, besides "auto"). */
    const std::vector<std::pair<std::string, VectorInstructions>> &
    vector_instructions_registry();

    /** Does this processor run @p instructions? */
    bool
    vector_instructions_supported(const VectorInstructions instructions);

    /** The name of @p instructions in the registry. */
    std::string
    vector_instructions_name(const VectorInstructions instructions);

    /**
     * Triangles per process above which `auto` takes AVX2 rather than
     * AVX-512: the benchmark plate (doc/performance.md, "Vector batches",
     * AMD EPYC, 32 MiB L3) ran 1.2 and 1.1 times faster with AVX-512 at
     * 20 000 and 45 000 triangles, 1.16 and 1.28 times slower at 97 000 and
     * 250 000, where the loop waits on memory.
     */
    constexpr unsigned int avx512_most_triangles = 65536;

    /** The set `auto` runs for @p triangles of this process, given the
     *  widest set @p widest the processor has. */
    inline VectorInstructions
    vector_instructions_for_mesh(const VectorInstructions widest,
                                 const std::size_t        triangles)
    {
      return widest == VectorInstructions::avx512 &&
                 triangles > avx512_most_triangles ?
               VectorInstructions::avx2 :
               widest;
    }

    /**
     * The instruction set of the prm entry value @p entry: "auto" is the
     * widest this processor has; a named set it does not have is an
     * InputError that names the entry and what is allowed here.
     */
    VectorInstructions
    resolve_vector_instructions(const std::string &entry);
  } // namespace discrete
} // namespace tmfdem

#endif
