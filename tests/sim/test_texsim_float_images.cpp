// texsim with a float image (OpenEXR, written here by OpenImageIO): values outside 0..1 are
// clamped with a one-line note naming the file; an image in range gives no note.
#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "cli_fixture.h"

TEST_F(TexsimCli, FloatImageValuesOutsideZeroToOneAreClampedWithANote) {
  queries("u,v,lod\n0.5,0.5,0\n");
  std::vector<float> px(8 * 8 * 3);
  for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 7) * 0.4f - 0.6f;  // -0.6 .. 1.8
  auto out = OIIO::ImageOutput::create((dir / "hdr.exr").string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open((dir / "hdr.exr").string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
              out->close());
  const Result r = run("sample -t hdr.exr -q q.csv -o r.csv");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("hdr.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("clamped"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // In range: no note.
  write_image(dir / "ldr.png", 8, 8, 3, [](int x, int, int) { return x; });
  EXPECT_EQ(run("sample -t ldr.png -q q.csv -o r.csv").err, "");
}
