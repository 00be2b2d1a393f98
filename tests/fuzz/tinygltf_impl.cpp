// tinygltf and stb_image compiled from Debian's headers (libtinygltf-dev, libstb-dev) into the fuzz
// targets, with the same coverage and sanitizers as the generator, in place of the shared libraries
// the normal build links (-ltinygltf -lstb): so that libFuzzer sees inside the glTF parser and the
// image decoder, and ASan and UBSan check them too.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
