// visp_track: the ViSP peer of modelc's cube tracker (build/cube/cube-track). ViSP's model-based
// edge tracker, vpMbGenericTracker with edge features only (EDGE_TRACKER: moving edges along the
// model's visible lines, pose by robust virtual visual servoing), on the same frames, from the same
// initial pose, writing the same CSV columns as cube-track:
//
//   frame,tx,ty,tz,tux,tuy,tuz,confidence,visible,matched,edges_ms,filter_ms
//
//   pose      cMo (object to camera) after track(): metres and theta-u radians (vpPoseVector)
//   confidence ViSP's projection error in degrees (vpMbTracker::computeCurrentProjectionError at the
//             tracked pose: the mean angle between the image gradient and the model lines, 0..90,
//             lower is better; computed after track() and not timed). Not a 0..1 confidence.
//   visible   moving-edge sites in the pose estimate (getNbFeaturesEdge)
//   matched   of those, the sites whose final robust (M-estimator) weight is above 0.5: the inliers
//   edges_ms  0 (ViSP has no separate edge stage)
//   filter_ms wall time of tracker.track(I) alone (steady clock), ms
//
// Frame 0 (--first) is initialised with initFromPose(I, cMo) from the .pos file and then tracked
// like every other frame, as cube-track does. When track() throws (ViSP: too few moving edges), the
// row has the pose getPose() gives then, visible = matched = 0 and an empty confidence, and tracking
// goes on with the next frame (no re-initialisation).
//
//   visp_track --frames 'DIR/image%04d.pgm' --model cube.cao --settings cube.xml --init cube.0.pos
//              [--first K] [--count N] [--scale K] [--out FILE.csv] [--overlay DIR]
//              [--range R] [--sample-step S] [--mask-size M] [--me-threshold T] [--judge POSES.csv]
//
// --judge POSES.csv: no tracking; for each frame, ViSP's projection error (as the confidence column
// above) of the pose POSES.csv gives it (any tracker's CSV with frame, tx..tuz), written as the CSV
// "frame,error". ViSP's own measure of how well a pose's lines lie on the frame's gradients, so that
// where two trackers disagree a third party says which pose fits the image better. With --overlay
// DIR, each judged frame (every --overlay-every th from --first) is drawn as tracking draws it, at
// the judged pose, and with --overlay-ref REF.csv the visible lines of REF's pose for that frame too
// (green, 1 px): two trackers' poses on the one frame.
//
// --settings: ViSP's tracker XML (camera, moving-edge parameters, face angles, clipping), as
// loadConfigFile reads it. --scale K: each frame shrunk K times by a KxK box average (as cube-track's
// --scale) and the camera scaled to match (px/K, py/K, u0' = (u0+0.5)/K-0.5, v0' likewise); the
// moving-edge search range and sample step are divided by K (rounded up; at least 1) unless given.
// --overlay DIR: DIR/frameNNNN.png for every 20th frame (--overlay-every N) and the last: the frame, the model's lines
// that the tracker sees at the tracked pose (red, 2 px), over the whole cube's 12 edges (yellow, 1 px,
// hidden ones too). (The moving-edge sites are not drawn: at the end of track() ViSP has already
// resampled them along the new pose's lines for the next frame.)
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpPoseVector.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/mbt/vpMbGenericTracker.h>
#include <visp3/me/vpMe.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

const char *usage =
    "usage: visp_track --frames PATTERN --model FILE.cao --settings FILE.xml --init FILE.pos [options]\n"
    "  --frames PATTERN   frame files, printf pattern with one integer, e.g. 'dir/image%04d.pgm'\n"
    "  --first K          first frame number (default 0)\n"
    "  --count N          frames to track (default: until the next file is missing)\n"
    "  --model FILE.cao   ViSP CAD model\n"
    "  --settings FILE    ViSP tracker XML (camera, moving edges, faces, clipping)\n"
    "  --init FILE.pos    first frame's cMo: tx ty tz (m) tux tuy tuz (rad)\n"
    "  --scale K          shrink frames K times (box average), camera scaled to match (default 1)\n"
    "  --range R          moving-edge search range, pixels (default: the XML's / K, rounded up)\n"
    "  --sample-step S    moving-edge sample step, pixels (default: the XML's / K)\n"
    "  --mask-size M      moving-edge mask size (default: the XML's)\n"
    "  --me-threshold T   moving-edge contrast threshold (default: the XML's)\n"
    "  --no-error         leave the confidence column empty (skip the projection error)\n"
    "  --out FILE         CSV (default: standard output)\n"
    "  --overlay DIR      DIR/frameNNNN.png every 20th frame and the last\n"
    "  --overlay-every N  every Nth frame instead (default 20)\n"
    "  --judge POSES.csv  no tracking: ViSP's projection error of each frame's pose in POSES.csv\n"
    "                     (columns frame, tx..tuz), written as the CSV frame,error; with --overlay, each\n"
    "                     judged frame drawn at that pose\n"
    "  --overlay-ref R.csv  with --judge and --overlay: R's pose of each frame drawn too (green)\n";

struct Options {
  std::string frames, model, settings, init, out, overlay, judge, overlay_ref;
  long first = 0, count = -1, scale = 1, overlay_every = 20;
  long range = -1, mask_size = -1;
  double sample_step = -1, me_threshold = -1;
  bool error = true;
};

[[noreturn]] void die(int status, const std::string &msg)
{
  std::cerr << "visp_track: " << msg << "\n";
  std::exit(status);
}

double number(const char *opt, const char *v)
{
  if (!v) die(2, std::string(opt) + ": missing value");
  char *end;
  double d = std::strtod(v, &end);
  if (end == v || *end || !std::isfinite(d)) die(2, std::string(opt) + " " + v + ": expected a number");
  return d;
}

Options parse(int argc, char **argv)
{
  Options o;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : nullptr;
    auto str = [&](std::string &s) {
      if (!v) die(2, std::string(a) + ": missing value");
      s = v, i++;
    };
    auto num = [&]() { double d = number(a, v); i++; return d; };
    if (!std::strcmp(a, "--help") || !std::strcmp(a, "-h")) { std::cout << usage; std::exit(0); }
    else if (!std::strcmp(a, "--frames")) str(o.frames);
    else if (!std::strcmp(a, "--model")) str(o.model);
    else if (!std::strcmp(a, "--settings")) str(o.settings);
    else if (!std::strcmp(a, "--init")) str(o.init);
    else if (!std::strcmp(a, "--out")) str(o.out);
    else if (!std::strcmp(a, "--overlay")) str(o.overlay);
    else if (!std::strcmp(a, "--judge")) str(o.judge);
    else if (!std::strcmp(a, "--overlay-ref")) str(o.overlay_ref);
    else if (!std::strcmp(a, "--first")) o.first = (long)num();
    else if (!std::strcmp(a, "--count")) o.count = (long)num();
    else if (!std::strcmp(a, "--scale")) o.scale = (long)num();
    else if (!std::strcmp(a, "--range")) o.range = (long)num();
    else if (!std::strcmp(a, "--sample-step")) o.sample_step = num();
    else if (!std::strcmp(a, "--mask-size")) o.mask_size = (long)num();
    else if (!std::strcmp(a, "--me-threshold")) o.me_threshold = num();
    else if (!std::strcmp(a, "--overlay-every")) o.overlay_every = (long)num();
    else if (!std::strcmp(a, "--no-error")) o.error = false;
    else die(2, std::string("unknown option ") + a + "\n" + usage);
  }
  if (o.frames.empty() || o.model.empty() || o.settings.empty() || o.init.empty())
    die(2, std::string("--frames, --model, --settings and --init are required\n") + usage);
  if (o.scale < 1 || o.scale > 16) die(2, "--scale: expected 1..16");
  if (o.first < 0) die(2, "--first: expected >= 0");
  if (o.overlay_every < 1) die(2, "--overlay-every: expected >= 1");
  if (!o.overlay_ref.empty() && (o.judge.empty() || o.overlay.empty()))
    die(2, "--overlay-ref: only with --judge and --overlay");
  return o;
}

std::string frame_path(const Options &o, long k)
{
  char buf[4096];
  int n = std::snprintf(buf, sizeof buf, o.frames.c_str(), (int)k);
  if (n < 0 || n >= (int)sizeof buf) die(2, "--frames: pattern too long");
  return buf;
}

bool exists(const std::string &p)
{
  std::ifstream f(p.c_str());
  return f.good();
}

// ViSP's .pos: six numbers, tx ty tz tux tuy tuz; '#' starts a comment.
vpPoseVector read_pose(const std::string &path)
{
  std::ifstream f(path.c_str());
  if (!f) die(1, path + ": cannot open");
  std::vector<double> v;
  std::string line;
  while (std::getline(f, line) && v.size() < 6) {
    line = line.substr(0, line.find('#'));
    std::istringstream s(line);
    double d;
    while (v.size() < 6 && s >> d) v.push_back(d);
  }
  if (v.size() != 6) die(1, path + ": expected six numbers tx ty tz tux tuy tuz");
  return vpPoseVector(v[0], v[1], v[2], v[3], v[4], v[5]);
}

// KxK box average, rounded to nearest; the last partial rows/columns dropped (as cube-track).
void shrink(const vpImage<unsigned char> &in, vpImage<unsigned char> &out, unsigned K)
{
  if (K == 1) { out = in; return; }
  const unsigned h = in.getHeight() / K, w = in.getWidth() / K, n = K * K;
  out.resize(h, w);
  for (unsigned i = 0; i < h; i++)
    for (unsigned j = 0; j < w; j++) {
      unsigned s = 0;
      for (unsigned di = 0; di < K; di++) {
        const unsigned char *row = in[i * K + di] + j * K;
        for (unsigned dj = 0; dj < K; dj++) s += row[dj];
      }
      out[i][j] = (unsigned char)((s + n / 2) / n);
    }
}

// The poses of a tracker's CSV (a header naming frame, tx, ty, tz, tux, tuy, tuz), by frame.
std::map<long, vpPoseVector> read_poses(const std::string &path)
{
  std::ifstream f(path.c_str());
  if (!f) die(1, path + ": cannot open");
  std::string line;
  std::vector<std::string> head;
  if (!std::getline(f, line)) die(1, path + ": empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();   // a CSV written with CRLF line ends
  {
    std::istringstream s(line);
    std::string c;
    while (std::getline(s, c, ',')) head.push_back(c);
  }
  const char *want[7] = {"frame", "tx", "ty", "tz", "tux", "tuy", "tuz"};
  size_t col[7];
  for (int i = 0; i < 7; i++) {
    col[i] = std::find(head.begin(), head.end(), want[i]) - head.begin();
    if (col[i] == head.size()) die(1, path + ":1: no column " + want[i]);
  }
  std::map<long, vpPoseVector> poses;
  for (long n = 2; std::getline(f, line); n++) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> cell;
    std::istringstream s(line);
    std::string c;
    while (std::getline(s, c, ',')) cell.push_back(c);
    double v[7];
    for (int i = 0; i < 7; i++) {
      char *end = nullptr;
      v[i] = col[i] < cell.size() ? std::strtod(cell[col[i]].c_str(), &end) : 0;
      if (col[i] >= cell.size() || end == cell[col[i]].c_str() || *end || !std::isfinite(v[i]))
        die(1, path + ":" + std::to_string(n) + ": " + want[i] + ": expected a number");
    }
    poses[(long)v[0]] = vpPoseVector(v[1], v[2], v[3], v[4], v[5], v[6]);
  }
  return poses;
}

void write_overlay(const std::string &dir, long k, const vpImage<unsigned char> &I, vpMbGenericTracker &tracker,
                   const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam, const vpHomogeneousMatrix *ref = nullptr)
{
  vpImage<vpRGBa> C;
  vpImageConvert::convert(I, C);
  // the whole model (hidden edges too), thin
  for (const auto &m : tracker.getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, true))
    if (m.size() == 5 && m[0] == 0)
      vpImageDraw::drawLine(C, vpImagePoint(m[1], m[2]), vpImagePoint(m[3], m[4]), vpColor::yellow, 1);
  // the lines the tracker uses, thicker
  for (const auto &m : tracker.getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, false))
    if (m.size() == 5 && m[0] == 0)
      vpImageDraw::drawLine(C, vpImagePoint(m[1], m[2]), vpImagePoint(m[3], m[4]), vpColor::red, 2);
  // another tracker's pose of the frame, its visible lines over the rest
  if (ref)
    for (const auto &m : tracker.getModelForDisplay(I.getWidth(), I.getHeight(), *ref, cam, false))
      if (m.size() == 5 && m[0] == 0)
        vpImageDraw::drawLine(C, vpImagePoint(m[1], m[2]), vpImagePoint(m[3], m[4]), vpColor::green, 1);
  char name[64];
  std::snprintf(name, sizeof name, "/frame%04ld.png", k);
  vpImageIo::write(C, dir + name);
}

} // namespace

int main(int argc, char **argv)
{
  const Options o = parse(argc, argv);
  const unsigned K = (unsigned)o.scale;
  try {
    vpImage<unsigned char> raw, I;
    const std::string p0 = frame_path(o, o.first);
    if (!exists(p0)) die(1, p0 + ": missing");
    vpImageIo::read(raw, p0);
    shrink(raw, I, K);

    vpMbGenericTracker tracker(1, vpMbGenericTracker::EDGE_TRACKER);
    tracker.loadConfigFile(o.settings, false);
    vpCameraParameters cam;
    tracker.getCameraParameters(cam);
    vpMe me = tracker.getMovingEdge();
    if (K > 1) {
      cam.initPersProjWithoutDistortion(cam.get_px() / K, cam.get_py() / K, (cam.get_u0() + 0.5) / K - 0.5,
                                        (cam.get_v0() + 0.5) / K - 0.5);
      me.setRange(std::max(1u, (me.getRange() + K - 1) / K));
      me.setSampleStep(std::max(1.0, std::ceil(me.getSampleStep() / K)));
    }
    if (o.range > 0) me.setRange((unsigned)o.range);
    if (o.sample_step > 0) me.setSampleStep(o.sample_step);
    if (o.mask_size > 0) me.setMaskSize((unsigned)o.mask_size);
    if (o.me_threshold > 0) me.setThreshold(o.me_threshold);
    tracker.setMovingEdge(me);
    {
      // the .cao parser reports to standard output, which may be the CSV: send it to standard error
      std::streambuf *saved = std::cout.rdbuf(std::cerr.rdbuf());
      tracker.loadModel(o.model);
      std::cout.rdbuf(saved);
    }
    tracker.setCameraParameters(cam);
    std::fprintf(stderr,
                 "visp_track: ViSP %d.%d.%d, %ux%u, camera px %.4f py %.4f u0 %.4f v0 %.4f; moving edges: mask size %u, "
                 "masks %u, range %u, threshold %g, mu1 %g, mu2 %g, sample step %g\n",
                 VISP_VERSION_MAJOR, VISP_VERSION_MINOR, VISP_VERSION_PATCH, I.getWidth(), I.getHeight(), cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(),
                 me.getMaskSize(), me.getMaskNumber(), me.getRange(), me.getThreshold(), me.getMu1(), me.getMu2(),
                 me.getSampleStep());

    vpHomogeneousMatrix cMo(read_pose(o.init));
    tracker.initFromPose(I, cMo);

    if (!o.judge.empty()) {   // no tracking: ViSP's projection error of the given poses
      const std::map<long, vpPoseVector> poses = read_poses(o.judge);
      std::map<long, vpPoseVector> refs;
      if (!o.overlay_ref.empty()) refs = read_poses(o.overlay_ref);
      std::ostringstream csv;
      csv << "frame,error\n";
      char row[128];
      for (const auto &fp : poses) {
        const long k = fp.first;
        if (k < o.first || (o.count >= 0 && k >= o.first + o.count)) continue;
        const std::string p = frame_path(o, k);
        if (!exists(p)) die(1, p + ": missing");
        vpImageIo::read(raw, p);
        shrink(raw, I, K);
        std::snprintf(row, sizeof row, "%ld,%.4f\n", k,
                      tracker.computeCurrentProjectionError(I, vpHomogeneousMatrix(fp.second), cam));
        csv << row;
        if (!o.overlay.empty() && (k - o.first) % o.overlay_every == 0) {
          const auto r = refs.find(k);
          const vpHomogeneousMatrix ref = r != refs.end() ? vpHomogeneousMatrix(r->second) : vpHomogeneousMatrix();
          write_overlay(o.overlay, k, I, tracker, vpHomogeneousMatrix(fp.second), cam, r != refs.end() ? &ref : nullptr);
        }
      }
      if (o.out.empty()) std::cout << csv.str();
      else {
        std::ofstream f(o.out.c_str());
        f << csv.str();
        if (!f) die(1, o.out + ": cannot write");
      }
      return 0;
    }

    std::ostringstream csv;
    csv << "frame,tx,ty,tz,tux,tuy,tuz,confidence,visible,matched,edges_ms,filter_ms\n";
    char row[512];
    long done = 0, failed = 0;
    std::vector<double> ms;
    for (long k = o.first; o.count < 0 || k < o.first + o.count; k++) {
      if (k > o.first) {
        const std::string p = frame_path(o, k);
        if (!exists(p)) {
          if (o.count >= 0) die(1, p + ": missing");
          break;
        }
        vpImageIo::read(raw, p);
        shrink(raw, I, K);
      }
      bool ok = true;
      const auto t0 = std::chrono::steady_clock::now();
      try {
        tracker.track(I);
      } catch (const vpException &e) {
        ok = false;
        failed++;
        std::fprintf(stderr, "visp_track: frame %ld: track() failed: %s\n", k, e.getStringMessage().c_str());
      }
      const auto t1 = std::chrono::steady_clock::now();
      const double t_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
      ms.push_back(t_ms);
      tracker.getPose(cMo);
      const vpPoseVector pv(cMo);
      unsigned used = ok ? tracker.getNbFeaturesEdge() : 0, kept = 0;
      const vpColVector w = tracker.getRobustWeights();
      for (unsigned i = 0; ok && i < w.size(); i++) kept += w[i] > 0.5;
      char conf[32] = "";
      if (o.error && ok) std::snprintf(conf, sizeof conf, "%.4f", tracker.computeCurrentProjectionError(I, cMo, cam));
      std::snprintf(row, sizeof row, "%ld,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%s,%u,%u,0,%.3f\n", k, pv[0], pv[1], pv[2],
                    pv[3], pv[4], pv[5], conf, used, kept, t_ms);
      csv << row;
      done++;
      if (!o.overlay.empty()) {
        const bool last = o.count >= 0 ? k == o.first + o.count - 1 : !exists(frame_path(o, k + 1));
        if ((k - o.first) % o.overlay_every == 0 || last) write_overlay(o.overlay, k, I, tracker, cMo, cam);
      }
    }
    if (o.out.empty()) std::cout << csv.str();
    else {
      std::ofstream f(o.out.c_str());
      f << csv.str();
      if (!f) die(1, o.out + ": cannot write");
    }
    std::sort(ms.begin(), ms.end());
    if (!ms.empty())
      std::fprintf(stderr, "visp_track: %ld frames (%ld failed), track() ms per frame: median %.3f, mean %.3f, max %.3f\n", done, failed,
                   ms[ms.size() / 2], [&] { double s = 0; for (double m : ms) s += m; return s / ms.size(); }(),
                   ms.back());
  } catch (const vpException &e) {
    die(1, std::string("ViSP: ") + e.getStringMessage());
  }
  return 0;
}
