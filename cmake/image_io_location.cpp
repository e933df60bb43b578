// Compiled into each program that links the installed refract::core (refractConfig.cmake
// adds it, with REFRACT_IMAGE_IO_INSTALLED the prefix's lib/refract/ module): a statically
// linked core finds the image module of the prefix it was installed with (core/image_io.cpp).
extern "C" __attribute__((weak)) const char* refract_image_io_installed() { return REFRACT_IMAGE_IO_INSTALLED; }
