// File > Export video under xvfb-run: the clip as an H.264 MP4 at 30 fps,
// every frame there, showing what the GIF export (the same rendering) shows
// at the same time; a failed export leaves no file. Both files are read back
// with libavformat (FFmpeg reads GIFs too).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;
using editor_test::runEditor;

struct DecodedVideo {
  std::string codec;
  std::vector<eng::Image> frames;  // RGBA, in presentation order
};

// Converts each frame the decoder has ready to RGBA.
void receiveFrames(AVCodecContext* decoder, AVFrame* frame, DecodedVideo& video) {
  while (avcodec_receive_frame(decoder, frame) == 0) {
    SwsContext* scale = sws_getContext(frame->width, frame->height, AVPixelFormat(frame->format), frame->width, frame->height,
                                       AV_PIX_FMT_RGBA, SWS_POINT, nullptr, nullptr, nullptr);
    eng::Image image;
    image.width = frame->width;
    image.height = frame->height;
    image.rgba8.resize(size_t(frame->width) * size_t(frame->height) * 4);
    uint8_t* planes[4] = {image.rgba8.data(), nullptr, nullptr, nullptr};
    const int strides[4] = {frame->width * 4, 0, 0, 0};
    sws_scale(scale, frame->data, frame->linesize, 0, frame->height, planes, strides);
    sws_freeContext(scale);
    video.frames.push_back(std::move(image));
  }
}

// Every frame of the file's video stream (empty when it cannot be read).
DecodedVideo decodeVideo(const fs::path& path) {
  DecodedVideo video;
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, path.c_str(), nullptr, nullptr) < 0) return video;
  const AVCodec* codec = nullptr;
  const int stream = avformat_find_stream_info(input, nullptr) >= 0 ? av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0) : -1;
  AVCodecContext* decoder = stream >= 0 ? avcodec_alloc_context3(codec) : nullptr;
  if (decoder && avcodec_parameters_to_context(decoder, input->streams[stream]->codecpar) >= 0 && avcodec_open2(decoder, codec, nullptr) >= 0) {
    video.codec = avcodec_get_name(codec->id);
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    while (av_read_frame(input, packet) >= 0) {
      if (packet->stream_index == stream && avcodec_send_packet(decoder, packet) == 0) receiveFrames(decoder, frame, video);
      av_packet_unref(packet);
    }
    if (avcodec_send_packet(decoder, nullptr) == 0) receiveFrames(decoder, frame, video);
    av_frame_free(&frame);
    av_packet_free(&packet);
  }
  avcodec_free_context(&decoder);
  avformat_close_input(&input);
  return video;
}

// The largest colour distance (R + G + B) between two same-sized images'
// 8x8 block averages: the GIF's dithering and the video's compression noise
// average out, a changed mouth does not.
double blockDifference(const eng::Image& a, const eng::Image& b) {
  constexpr int kBlock = 8;
  double largest = 0;
  for (int by = 0; by + kBlock <= a.height; by += kBlock)
    for (int bx = 0; bx + kBlock <= a.width; bx += kBlock) {
      glm::ivec3 sa{0}, sb{0};
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) sa += editor_test::pixel(a, x, y), sb += editor_test::pixel(b, x, y);
      largest = std::max(largest, double(editor_test::colourDistance(sa, sb)) / (kBlock * kBlock));
    }
  return largest;
}

TEST(EditorVideoExport, TheClipAsH264At30FpsShowsWhatTheGifShows) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_video_export");
  // A 2 s clip: neutral at 0, happy at 1 s (cosine), held to the end.
  testing_support::writeFile(dir / "export.txt",
                             "0.2 timeline-key-emotion neutral 0 cosine\n"
                             "0.3 timeline-key-emotion happy 1 cosine\n"
                             "0.4 export-video clip.mp4\n"
                             "0.5 export-gif clip.gif\n"
                             "0.6 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script export.txt", 60.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  EXPECT_NE(run.log.find("exported clip.mp4: clip 'untitled', 60 frames at 30 fps"), std::string::npos) << run.log;
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);

  const DecodedVideo video = decodeVideo(dir / "clip.mp4"), gif = decodeVideo(dir / "clip.gif");
  EXPECT_EQ(video.codec, "h264");
  ASSERT_EQ(video.frames.size(), 60u) << "2 s at 30 fps";
  ASSERT_EQ(gif.frames.size(), 40u) << "2 s at 20 fps";
  EXPECT_EQ(video.frames[0].width, 384);
  EXPECT_EQ(video.frames[0].height, 384);
  // The same times: 0 s (video frame 0, GIF frame 0), 0.5 s (15, 10), 1 s (30, 20).
  // For a person to look at: the same moment from both files.
  ASSERT_TRUE(eng::writePng(dir / "video_30.png", 384, 384, video.frames[30].rgba8));
  ASSERT_TRUE(eng::writePng(dir / "gif_20.png", 384, 384, gif.frames[20].rgba8));
  // Measured: about 10 between the two files at one time (palette and compression), 400 from neutral to happy.
  const double moved = blockDifference(video.frames[0], video.frames[30]);
  EXPECT_GT(moved, 100.0) << "the mouth opens between 0 and 1 s";
  for (const auto& [v, g] : {std::pair{0, 0}, std::pair{15, 10}, std::pair{30, 20}, std::pair{57, 38}}) {
    const double same = blockDifference(video.frames[size_t(v)], gif.frames[size_t(g)]);
    EXPECT_LT(same, 25.0) << "video frame " << v << " against GIF frame " << g << " (neutral against happy: " << moved << ")";
  }
}

TEST(EditorVideoExport, AFailedExportLeavesNoFile) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_video_export_fails");
  testing_support::writeFile(dir / "fail.txt",
                             "0.2 export-video empty.mp4\n"  // no tracks yet
                             "0.3 timeline-key-emotion happy 0.5 cosine\n"
                             "0.4 export-video other.mp4 talk\n"  // no such clip in the project
                             "0.5 export-video clip.avi\n"  // not a container the writer makes
                             "0.6 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script fail.txt", 30.0f);
  EXPECT_EQ(run.exitCode, 1) << run.log;
  EXPECT_NE(run.log.find("empty.mp4: not exported: the clip has no tracks"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("other.mp4: not exported: the project has no clip 'talk'"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("clip.avi: not exported: "), std::string::npos) << run.log;
  for (const char* name : {"empty.mp4", "other.mp4", "clip.avi"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);
  // A script's arguments are checked before the window opens.
  testing_support::writeFile(dir / "args.txt", "0.1 export-video\n");
  EXPECT_NE(runEditor(dir, "--script args.txt", 5.0f).log.find("'export-video' takes 1 or 2 argument(s), got 0"), std::string::npos);
}

}  // namespace
