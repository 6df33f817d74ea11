/* Preloaded into the GPU tests under `make sanitize` (Makefile): dlclose does nothing, so every
 * library stays loaded until the process exits. Mesa's EGL unloads its driver (swrast_dri.so and
 * the libdrm and libsensors it pulled in) at eglTerminate; a block the driver keeps in its static
 * data then loses the globals that point to it, and LeakSanitizer reports it as a direct leak in
 * "<unknown module>", which no suppression can name (seen with Mesa 22.3: 128 bytes, realloc).
 * Kept loaded, such blocks stay reachable like those of every other library, while a leak of our
 * own code, which is never unloaded, is still reported. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
