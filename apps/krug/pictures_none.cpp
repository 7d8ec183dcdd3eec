// Pictures when krug is built without Cairo: none (the app says so once on stderr).
#include "pictures.hpp"

namespace krug::app {

bool pictures_available() { return false; }

bool write_picture(const Simulation&, const scenario::PictureSettings&, const std::string&, const std::filesystem::path&,
                   const std::string&) {
  return false;
}

}  // namespace krug::app
