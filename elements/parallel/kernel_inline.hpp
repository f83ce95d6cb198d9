#pragma once
/// \file XPL_KERNEL_INLINE: the pieces of an element's force kernel (hex/hex_kernel.hpp,
/// shell/shell4r_kernel.hpp) are inlined into it whatever the inliner's budget, so that a kernel
/// compiles as one function, as when its pieces were written out in it.

#define XPL_KERNEL_INLINE [[gnu::always_inline]] inline
