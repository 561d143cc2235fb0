#include <gtest/gtest.h>

#include "io/temp_dir.h"
#include "stillslam/io/image_files.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

TEST(ImageFiles, ExtensionsInAnyCase) {
  for (const char* name : {"a.png", "b.JPG", "c.jpeg", "d.bmp", "e.pgm", "f.tif", "g.TIFF"})
    EXPECT_TRUE(is_image_file(name)) << name;
  for (const char* name : {"a.txt", "b.png.txt", "png", "c.jpg~", "d.exr"}) EXPECT_FALSE(is_image_file(name)) << name;
}

TEST(ImageFiles, RegularImageFilesDirectlyInAFolderSorted) {
  test::TempDir dir;
  for (const char* name : {"c.png", "a.PNG", "b.pgm", "notes.txt", "sub/d.png"}) dir.write(name, "x");
  fs::create_directories(dir.path() / "folder.png");  // a folder, not a file
  const std::vector<fs::path> files = image_files_in(dir.path());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].filename(), "a.PNG");
  EXPECT_EQ(files[1].filename(), "b.pgm");
  EXPECT_EQ(files[2].filename(), "c.png");
}

}  // namespace
}  // namespace stillslam
