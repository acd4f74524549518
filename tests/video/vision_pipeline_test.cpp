// The pipeline and its runner on real video: the Hamilton clip produces tracks and events; a
// folder of frames with a corrupt one, a corrupt or truncated video file and a missing camera
// become events or clear errors; parameters change while it runs.
#include <fstream>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/pipeline_runner.hpp"
#include "facesocial/vision_pipeline.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

/// A bank of a few ORL people, normalised like detected faces (the pipeline's normaliser).
std::shared_ptr<ClassifierBank> small_bank() {
    auto bank = std::make_shared<ClassifierBank>();
    const FaceNormalizer n(bank->params().normalizer);
    for (const PersonImages& p : load_identity_folders(test::data() / "orl")) {
        std::vector<cv::Mat> faces;
        for (std::size_t i = 0; i < 3; ++i) {
            const cv::Mat img = load_image(p.images[i], ImageColor::Grey);
            faces.push_back(n.normalize(img, {0, 0, img.cols, img.rows}).pixels);
        }
        bank->add_faces(p.name, faces);
        if (bank->people().size() == 4) break;
    }
    bank->train();
    return bank;
}

std::string clip() { return (test::data() / "video_hamilton" / "short_hamilton_clip.mp4").string(); }

std::vector<PipelineResult> run_all(PipelineRunner& runner) {
    std::vector<PipelineResult> out;
    PipelineResult r;
    while (!runner.finished())
        if (runner.next(r, std::chrono::milliseconds(5000))) out.push_back(r);
    return out;
}

int count(const std::vector<PipelineResult>& results, PipelineEventKind kind) {
    int n = 0;
    for (const auto& r : results)
        for (const auto& e : r.events) n += e.kind == kind;
    return n;
}

}  // namespace

TEST(VisionPipeline, RealClipProducesTracksDecisionsAndEvents) {
    auto pipeline = std::make_shared<VisionPipeline>(small_bank());
    auto source = VideoSource::open(clip());
    EXPECT_FALSE(source->is_live());
    EXPECT_EQ(source->frame_count(), 275);
    RunnerParams rp;
    rp.result_queue = 1000;  // keep every result for the checks
    PipelineRunner runner(pipeline, std::move(source), rp);
    const auto results = run_all(runner);
    EXPECT_EQ(runner.error(), nullptr);
    ASSERT_EQ(results.size(), 276u);  // 275 frames + the end of the stream
    EXPECT_EQ(runner.stats().frames_processed, 275);
    EXPECT_EQ(runner.stats().frames_dropped, 0);
    EXPECT_EQ(results.back().status, FrameStatus::End);
    int frames_with_faces = 0;
    for (std::size_t i = 0; i + 1 < results.size(); ++i) {
        EXPECT_EQ(results[i].frame, static_cast<long long>(i));
        frames_with_faces += results[i].faces_detected > 0;
        for (const TrackReport& t : results[i].tracks) {
            EXPECT_GT(t.track_id, 0);
            if (t.seen) EXPECT_EQ(t.frame_decision.ranked.size(), 4u);
        }
    }
    EXPECT_GT(frames_with_faces, 100);
    const int started = count(results, PipelineEventKind::TrackStarted);
    EXPECT_GE(started, 2);  // the performer, then the audience after the cut
    EXPECT_GE(count(results, PipelineEventKind::DecisionMade), 1);
    EXPECT_EQ(count(results, PipelineEventKind::TrackLost), started);  // every track ends
    EXPECT_EQ(count(results, PipelineEventKind::StreamEnded), 1);
    EXPECT_TRUE(pipeline->snapshot().tracks.empty());
}

TEST(VisionPipeline, ParametersCanBeReadAndChangedBetweenFrames) {
    VisionPipeline pipeline(small_bank());
    auto source = VideoSource::open(clip());
    Frame f;
    for (int i = 0; i < 120; ++i) ASSERT_EQ(source->read(f), FrameStatus::Ok);  // into the performer shot
    const PipelineResult first = pipeline.process(f);
    EXPECT_EQ(pipeline.snapshot().frame, first.frame);
    EXPECT_EQ(pipeline.face_regions().size(), std::size_t(std::count_if(first.tracks.begin(), first.tracks.end(),
                                                                         [](const TrackReport& t) { return t.seen; })));
    PipelineParams p = pipeline.params();
    EXPECT_EQ(p.accumulator.window, 25);
    p.accumulator.window = 5;
    p.front_end.frontal.min_face_size = 300;  // no face that large in the clip
    pipeline.set_params(p);
    EXPECT_EQ(pipeline.params().accumulator.window, 5);
    ASSERT_EQ(source->read(f), FrameStatus::Ok);
    EXPECT_EQ(pipeline.process(f).faces_detected, 0);
    PipelineParams bad = p;
    bad.min_frames = 0;
    EXPECT_THROW(pipeline.set_params(bad), std::invalid_argument);
    bad = p;
    bad.front_end.frontal.cascade_file = "no_such_cascade.xml";
    EXPECT_THROW(pipeline.set_params(bad), FileError);
    EXPECT_EQ(pipeline.params().accumulator.window, 5);  // a refused change leaves the params alone
}

TEST(VisionPipeline, FolderWithACorruptFrameReportsItAndGoesOn) {
    test::TempDir dir;
    const auto images = list_images(test::data() / "caltech_faces1999_partial" / "images");
    for (int i = 0; i < 3; ++i) save_image(dir / ("frame" + std::to_string(i * 2) + ".jpg"), load_image(images[std::size_t(i)]));
    std::ofstream(dir / "frame1.jpg") << "not a jpeg";
    auto source = VideoSource::open(dir.path().string());
    EXPECT_EQ(source->frame_count(), 4);
    auto pipeline = std::make_shared<VisionPipeline>(small_bank());
    PipelineRunner runner(pipeline, std::move(source));
    const auto results = run_all(runner);
    ASSERT_EQ(results.size(), 5u);
    EXPECT_EQ(results[1].status, FrameStatus::Skipped);
    EXPECT_NE(results[1].events.at(0).message.find("frame1.jpg"), std::string::npos);
    EXPECT_EQ(results[2].status, FrameStatus::Ok);
    EXPECT_GE(results[2].faces_detected, 1);
    EXPECT_EQ(results[4].status, FrameStatus::End);
    EXPECT_EQ(runner.stats().frames_processed, 3);
}

TEST(VisionPipeline, CorruptVideoMissingFileAndMissingCameraGiveClearErrors) {
    test::TempDir dir;
    std::ofstream(dir / "garbage.mp4") << std::string(5000, 'x');
    EXPECT_THROW(VideoSource::open((dir / "garbage.mp4").string()), FileError);
    EXPECT_THROW(VideoSource::open((dir / "missing.mp4").string()), FileError);
    EXPECT_THROW(VideoSource::open(""), FileError);
    try {
        VideoSource::open("7");
        ADD_FAILURE() << "camera 7 opened";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("camera 7"), std::string::npos);
    }
    // The first 40% of the real clip: it opens (or is refused) and then ends cleanly.
    std::ifstream in(clip(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir / "truncated.mp4", std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 5);
    try {
        auto source = VideoSource::open((dir / "truncated.mp4").string());
        Frame f;
        long long frames = 0;
        FrameStatus s;
        while ((s = source->read(f)) == FrameStatus::Ok) ++frames;
        EXPECT_EQ(s, FrameStatus::End);
        EXPECT_LT(frames, 275);
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("truncated.mp4"), std::string::npos);
    }
    EXPECT_THROW(VisionPipeline(nullptr), std::invalid_argument);
    VisionPipeline pipeline(small_bank());
    Frame empty;
    EXPECT_THROW(pipeline.process(empty), std::invalid_argument);
}

TEST(PipelineRunner, ASlowConsumerNeverBlocksThePipeline) {
    auto pipeline = std::make_shared<VisionPipeline>(small_bank());
    RunnerParams rp;
    rp.result_queue = 2;
    PipelineRunner runner(pipeline, VideoSource::open(clip()), rp);
    // Take nothing until the whole clip is processed: the pipeline runs on, dropping results.
    for (int i = 0; i < 600 && runner.stats().frames_processed < 275; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_EQ(runner.stats().frames_processed, 275);
    EXPECT_EQ(runner.stats().results_dropped, 276 - 2);
    PipelineResult r;
    ASSERT_TRUE(runner.next(r, std::chrono::milliseconds(100)));
    ASSERT_TRUE(runner.next(r, std::chrono::milliseconds(100)));
    EXPECT_EQ(r.status, FrameStatus::End);
    EXPECT_FALSE(runner.next(r, std::chrono::milliseconds(10)));
    EXPECT_TRUE(runner.finished());
}
