/* Preloaded (after the ASan runtime) into the C++ test programs of the sanitizer run
 * (Scripts/sanitize.sh): makes dlclose() a no-op, so every shared object stays mapped until
 * the process ends.
 *
 * Why: Mesa's GLX stack dlopen()s its driver (llvmpipe) and dlclose()s it when the X display
 * closes. Blocks the driver still pointed to from its own globals then look unreachable to
 * LeakSanitizer's exit-time scan (the globals are unmapped), and the report cannot even
 * name their allocator ("<unknown module>"), so no library-name suppression can match.
 * Keeping modules loaded removes exactly these false reports; leak detection stays on for
 * everything, our code included. Our libraries are never dlclose()d by the C++ tests. */
int dlclose(void* handle)
{
  (void)handle;
  return 0;
}
