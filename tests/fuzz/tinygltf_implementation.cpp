// tinygltf's implementation, compiled into the fuzz harnesses so that the sanitizers
// and libFuzzer's coverage see inside it (the library links the Debian shared
// library instead). As in that library, with stb's image code, which FinFlex never
// calls (it sets an image loader that decodes nothing).
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
