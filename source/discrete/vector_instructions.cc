#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/vector_instructions.h>

namespace tmfdem
{
  namespace discrete
  {
    const std::vector<std::pair<std::string, VectorInstructions>> &
    vector_instructions_registry()
    {
      static const std::vector<std::pair<std::string, VectorInstructions>>
        sets = {{"AVX-512", VectorInstructions::avx512},
                {"AVX2", VectorInstructions::avx2},
                {"SSE2", VectorInstructions::sse2},
                {"none", VectorInstructions::none}};
      return sets;
    }

    bool
    vector_instructions_supported(const VectorInstructions instructions)
    {
#if defined(__x86_64__) || defined(__i386__)
      switch (instructions)
        {
          case VectorInstructions::avx512:
            return __builtin_cpu_supports("avx512f");
          case VectorInstructions::avx2:
            return __builtin_cpu_supports("avx2");
          case VectorInstructions::sse2:
          case VectorInstructions::none:
            return true;
        }
      return false;
#else
      // elsewhere the batches are compiled for the target's own vectors
      return instructions == VectorInstructions::none ||
             instructions == VectorInstructions::sse2;
#endif
    }

    std::string
    vector_instructions_name(const VectorInstructions instructions)
    {
      for (const auto &[name, set] : vector_instructions_registry())
        if (set == instructions)
          return name;
      return "?";
    }

    VectorInstructions
    resolve_vector_instructions(const std::string &entry)
    {
      std::string here;
      for (const auto &[name, set] : vector_instructions_registry())
        if (vector_instructions_supported(set))
          here += (here.empty() ? "" : ", ") + name;
      for (const auto &[name, set] : vector_instructions_registry())
        if (entry == "auto" ? vector_instructions_supported(set) :
                              entry == name)
          {
            if (!vector_instructions_supported(set))
              throw InputError(
                "Discrete mechanics/Vector instructions = " + entry +
                ": this processor does not have them; "
                "allowed here are auto, " +
                here + ".");
            return set;
          }
      throw InputError("Discrete mechanics/Vector instructions = " + entry +
                       ": unknown; allowed are auto, " + here + ".");
    }
  } // namespace discrete
} // namespace tmfdem
