// Image lists and text tables (io/text_table, TUM rgb.txt/depth.txt and
// associations): the table with every field parsed as a number, the TUM
// association reader, and rgb/depth association of the file with itself.
#include "fuzz/fuzz_support.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/tum_dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto path = fuzz::input_file(data, size, "rgb.txt");
  fuzz::expect_error_or_result([&] {
    for (const TextRow& row : read_text_table(path)) {
      for (const std::string& field : row.fields) {
        fuzz::expect_error_or_result([&] { parse_double(field, path, row.line); });
        fuzz::expect_error_or_result([&] { parse_int64(field, path, row.line); });
      }
    }
  });
  fuzz::expect_error_or_result([&] { read_tum_associations(path); });
  fuzz::expect_error_or_result([&] { associate_tum_lists(path, path, 0.02); });
  return 0;
}
