# cmake -DSOURCE_DIR=client/web -DOUTPUT=web_assets_data.cpp -P embed_assets.cmake
# Writes every file of SOURCE_DIR into OUTPUT as a byte array, with its path and content type,
# in the table find_asset() (web_assets.hpp) reads. Files are sorted by name, so the output
# depends on the sources only.
file(GLOB files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/*")
list(SORT files)
set(arrays "")
set(table "")
set(k 0)
foreach(name ${files})
  if(IS_DIRECTORY "${SOURCE_DIR}/${name}")
    continue()
  endif()
  get_filename_component(ext "${name}" LAST_EXT)
  if(ext STREQUAL ".html")
    set(type "text/html; charset=utf-8")
  elseif(ext STREQUAL ".js")
    set(type "text/javascript; charset=utf-8")
  elseif(ext STREQUAL ".css")
    set(type "text/css; charset=utf-8")
  elseif(ext STREQUAL ".svg")
    set(type "image/svg+xml")
  elseif(ext STREQUAL ".png")
    set(type "image/png")
  else()
    set(type "text/plain; charset=utf-8")
  endif()
  file(READ "${SOURCE_DIR}/${name}" hex HEX)
  string(LENGTH "${hex}" digits)
  math(EXPR size "${digits} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," bytes "${hex}")
  string(APPEND arrays "const char asset_${k}[] = {${bytes}0};\n")
  string(APPEND table "    {\"/${name}\", \"${type}\", std::string_view(asset_${k}, ${size})},\n")
  math(EXPR k "${k} + 1")
endforeach()
file(WRITE "${OUTPUT}.tmp" "// Generated from ${SOURCE_DIR} by server/web/embed_assets.cmake; do not edit.
#include <array>
#include <string_view>

#include \"server/web/web_assets.hpp\"

namespace fnet::web {
namespace {
${arrays}
const Asset table[] = {
${table}};
}  // namespace

const Asset* find_asset(std::string_view path) {
  if (path == \"/\") path = \"/index.html\";
  for (const Asset& a : table)
    if (a.path == path) return &a;
  return nullptr;
}

}  // namespace fnet::web
")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
