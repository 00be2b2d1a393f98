#!/usr/bin/env python3
"""The stream page (stream.html, runtime/front/web) in headless Chromium against the native viewer.

    stream_check.py WEBDIR VIEW BUDGET OUT [--seed N]

WEBDIR is build.sh's output for a bake with --emit stream, VIEW that bake's native viewer, BUDGET its
budget.json (the stream's size and drawable_at), OUT a scratch folder. Serves WEBDIR from a local
server that can also send the stream cut at byte k, damaged, or level by level with pauses, loads the
page for each in one Chromium (tests/web/cdp.py's), and checks every frame against the native
viewer's PPM of the level the page should draw: the level that follows from drawable_at for cuts
(--depth d), the native reader's (--stream) for damaged streams. Prints one line per check in
tests/tap.sh's format; exits 1 when any failed.
"""
import argparse
import base64
import json
import os
import random
import struct
import subprocess
import sys
import threading
import time
import zlib
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser  # noqa: E402

PREFIX = 'web: stream: '
failed = 0


def ok(name):
    print('ok - ' + PREFIX + name, flush=True)


def notok(name, why):
    global failed
    failed += 1
    why = ' '.join(str(why).split())[:400]
    print('not ok - ' + PREFIX + name + ': ' + why, flush=True)


def check(name, problems):
    if problems:
        notok(name, '; '.join(problems))
    else:
        ok(name)


class Streams:
    """What the server sends: /web/FILE from WEBDIR, /cut/K.mcs the stream's first K bytes,
    /data/NAME one of the damaged copies, /slow/MS.mcs the whole stream with a pause of MS
    milliseconds after each level's record (drawable_at)."""

    def __init__(self, webdir, stream, drawable_at):
        self.webdir, self.stream, self.drawable_at = webdir, stream, drawable_at
        self.data = {}
        self.requests = []


def handler_for(streams):
    class Handler(BaseHTTPRequestHandler):
        def log_message(self, *args):
            pass

        def send_bytes(self, body, pieces=None, pause=0.0):
            self.send_response(200)
            self.send_header('Content-Type', 'application/octet-stream')
            self.send_header('Content-Length', str(len(body)))
            self.send_header('Cache-Control', 'no-store')
            self.end_headers()
            at = 0
            for end in (pieces or []) + [len(body)]:
                if end <= at or end > len(body):
                    continue
                self.wfile.write(body[at:end])
                self.wfile.flush()
                at = end
                if end < len(body):
                    time.sleep(pause)

        def do_GET(self):
            path = self.path.split('?', 1)[0]
            streams.requests.append(path)
            parts = path.strip('/').split('/')
            try:
                if parts[0] == 'web' and len(parts) == 2 and not parts[1].startswith('.'):
                    with open(os.path.join(streams.webdir, parts[1]), 'rb') as f:
                        body = f.read()
                    ctype = {'html': 'text/html', 'js': 'text/javascript', 'wasm': 'application/wasm'}.get(
                        parts[1].rsplit('.', 1)[-1], 'application/octet-stream')
                    self.send_response(200)
                    self.send_header('Content-Type', ctype)
                    self.send_header('Content-Length', str(len(body)))
                    self.end_headers()
                    self.wfile.write(body)
                elif parts[0] == 'cut' and len(parts) == 2:
                    self.send_bytes(streams.stream[:int(parts[1].split('.')[0])])
                elif parts[0] == 'data' and len(parts) == 2 and parts[1] in streams.data:
                    self.send_bytes(streams.data[parts[1]])
                elif parts[0] == 'slow' and len(parts) == 2:
                    self.send_bytes(streams.stream, list(streams.drawable_at), int(parts[1].split('.')[0]) / 1000)
                else:
                    self.send_error(404)
            except (OSError, ValueError):
                try:
                    self.send_error(404)
                except OSError:
                    pass
    return Handler


def read_ppm(path):
    with open(path, 'rb') as f:
        data = f.read()
    fields, at = [], 0
    while len(fields) < 4:   # "P6", width, height, 255, each followed by one whitespace byte
        end = at
        while data[end:end + 1] not in (b' ', b'\n', b'\t', b'\r'):
            end += 1
        fields.append(data[at:end])
        at = end + 1
    return int(fields[1]), int(fields[2]), data[at:]


def write_ppm(path, w, h, rgb):
    with open(path, 'wb') as f:
        f.write(b'P6\n%d %d\n255\n' % (w, h) + rgb)


def canvas_rgb(shot):
    rgba = base64.b64decode(shot['rgba'])
    rgb = bytearray(len(rgba) // 4 * 3)
    rgb[0::3], rgb[1::3], rgb[2::3] = rgba[0::4], rgba[1::4], rgba[2::4]
    return bytes(rgb), rgba


def differ(a, b):
    """pixels that differ between two RGB byte strings of one size"""
    if len(a) != len(b):
        return 'sizes %d and %d bytes' % (len(a), len(b))
    n = sum(1 for i in range(0, len(a), 3) if a[i:i + 3] != b[i:i + 3])
    return '%d of %d pixels differ' % (n, len(a) // 3) if n else ''


class Native:
    """The native viewer's frames and stream lines, each made once."""

    def __init__(self, view, out, size):
        self.view, self.out, self.size = view, out, size
        self.cache = {}

    def run(self, key, args):
        if key not in self.cache:
            ppm = os.path.join(self.out, 'native-%s.ppm' % key)
            p = subprocess.run([self.view, '--size', self.size, '--ppm', ppm] + args, capture_output=True, text=True)
            rgb = read_ppm(ppm)[2] if os.path.exists(ppm) else None
            self.cache[key] = (rgb, p.returncode, p.stdout, p.stderr.strip())
        return self.cache[key]

    def depth(self, d, view_args=(), tag='default'):
        return self.run('%s-depth%d' % (tag, d), ['--depth', str(d)] + list(view_args))[0]

    def stream(self, key, data):
        path = os.path.join(self.out, key + '.mcs')
        with open(path, 'wb') as f:
            f.write(data)
        return self.run('stream-' + key, ['--stream', path])


# evaluated in the page: the stream's end, the frame drawn after it, the status and the canvas
CANVAS_JS = '''
  const canvas = document.getElementById('view');
  const shot = () => {
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    let bin = '';
    for (let i = 0; i < data.length; i += 8192) bin += String.fromCharCode.apply(null, data.subarray(i, i + 8192));
    return btoa(bin);
  };
  const statusText = () => document.getElementById('status').textContent;
'''
END_JS = '''(async () => {''' + CANVAS_JS + '''
  const m = await window.modelc.ready;
  const state = await m.received;
  const frame = await m.idle();
  return { state: state, frame: frame, frames: m.frames(), status: statusText(), rgba: shot() };
})()'''
# polls while the stream arrives: the canvas whenever a deeper level has been drawn and the fetch
# has not ended, with the state and status line at that moment
PROGRESS_JS = '''(async () => {''' + CANVAS_JS + '''
  const m = await window.modelc.ready;
  const shots = [];
  let seen = 0;
  for (;;) {
    const s = m.stream(), f = m.last();
    if (f && !f.moving && f.model > seen && !s.done) {
      seen = f.model;
      shots.push({ frame: f, state: s, status: statusText(), rgba: shot() });
    }
    if (s.done) break;
    await new Promise((resolve) => setTimeout(resolve, 4));
  }
  await m.received;
  return { shots: shots, state: m.stream() };
})()'''


class Page:
    def __init__(self, browser, w, h):
        self.b = browser
        target = self.b.call('Target.createTarget', {'url': 'about:blank'})['targetId']
        self.session = self.b.call('Target.attachToTarget', {'targetId': target, 'flatten': True})['sessionId']
        self.b.call('Page.enable', session=self.session)
        self.b.call('Emulation.setDeviceMetricsOverride', {'width': w, 'height': h, 'deviceScaleFactor': 1,
                                                           'mobile': False}, session=self.session)

    def eval(self, url, js, timeout_ms=20000):
        self.b.call('Page.navigate', {'url': url}, session=self.session)
        self.b.wait_event('Page.loadEventFired', self.session)
        js = ('Promise.race([%s, new Promise((_, no) => setTimeout(() => no(new Error("no answer in %d ms")), %d))])'
              % (js, timeout_ms, timeout_ms))
        r = self.b.call('Runtime.evaluate', {'expression': js, 'awaitPromise': True, 'returnByValue': True},
                        session=self.session)
        if 'exceptionDetails' in r:
            raise RuntimeError('the page threw: %s' % r['exceptionDetails'].get('exception', {}).get(
                'description', r['exceptionDetails']))
        return r.get('result', {}).get('value')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('webdir')
    ap.add_argument('view')
    ap.add_argument('budget')
    ap.add_argument('out')
    ap.add_argument('--seed', type=int, default=12)
    ap.add_argument('--drive', help='tests/web/drive.js: also drive the page over the whole stream')
    args = ap.parse_args()
    budget = json.load(open(args.budget))
    name = os.path.basename(budget['stream']['file']).rsplit('.', 1)[0]
    with open(os.path.join(args.webdir, name + '.mcs'), 'rb') as f:
        stream = f.read()
    da = budget['stream']['drawable_at']
    total, levels = len(stream), len(da)
    html = open(os.path.join(args.webdir, 'stream.html')).read()
    w = int(html.split('width="')[1].split('"')[0])
    h = int(html.split('height="')[1].split('"')[0])
    size = '%dx%d' % (w, h)
    native = Native(args.view, args.out, size)
    depth_at = lambda k: sum(1 for e in da if e <= k)   # the deepest complete level of a k-byte prefix

    streams = Streams(args.webdir, stream, da)
    server = ThreadingHTTPServer(('127.0.0.1', 0), handler_for(streams))
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = 'http://127.0.0.1:%d' % server.server_address[1]
    page_url = lambda src: base + '/web/stream.html?stream=' + src

    b = None
    try:
        b = Browser(w + 40, h + 120)
        page = Page(b, w + 40, h + 120)
    except (RuntimeError, OSError, ValueError) as e:
        print('ok - %sthe stream page in Chromium # SKIP Chromium cannot start here: %s' % (PREFIX, e), flush=True)
        if b:
            b.close()
        server.shutdown()
        return 0
    try:
        t0 = time.time()

        def load(tag, src, js=END_JS):
            try:
                return page.eval(page_url(src), js)
            except (RuntimeError, OSError, ValueError) as e:
                notok(tag, e)
                return None

        saved = [0]

        def frame_against(r, ref, why_ref):
            rgb, _ = canvas_rgb(r)
            d = 'no native frame' if ref is None else differ(rgb, ref)
            if not d:
                return []
            saved[0] += 1   # the canvas kept for a look beside the native PPMs
            path = os.path.join(args.out, 'canvas-%d.ppm' % saved[0])
            write_ppm(path, w, h, rgb)
            return ['the canvas (%s) differs from %s: %s' % (path, why_ref, d)]

        def blank(r):
            _, rgba = canvas_rgb(r)
            return [] if not any(rgba) else ['the canvas was drawn on']

        # ---- the whole stream: the native frame of the full depth, from the bake and from its stream ----
        r = load('whole stream', '/web/%s.mcs' % name)
        if r:
            s, p = r['state'], []
            if not (s['ok'] and s['done'] and s['depth'] == levels and s['bytes'] == total and s['total'] == total):
                p.append('state %s' % json.dumps(s))
            if not r['frame'] or r['frame']['model'] != levels:
                p.append('frame %s' % r['frame'])
            line = 'stream: complete, depth %d, %d bytes' % (levels, total)
            if r['status'].split('\n')[-1] != line:
                p.append('status %r, expected its last line %r' % (r['status'], line))
            p += frame_against(r, native.depth(levels), 'the native viewer at --depth %d' % levels)
            p += frame_against(r, native.stream('whole', stream)[0], 'the native viewer of --stream')
            first = s['drawable'][0]['bytes'] if s['drawable'] else None
            check('whole stream (%d bytes): complete, depth %d of %d, the canvas equals the native viewer\'s '
                  '--depth %d and --stream frames pixel for pixel at %s; fetched %s' %
                  (total, s['depth'], levels, levels, size, '/'.join(
                      x for x in ('stream.html', name + '-stream.wasm', name + '.mcs')
                      if '/web/' + x in streams.requests)), p)

        # ---- driven through its handlers once the stream is in: drag, wheel, key as tests/web/drive.js ----
        if args.drive:
            drive = open(args.drive).read().strip().rstrip(';')
            try:
                r = page.eval(page_url('/web/%s.mcs' % name),
                              'window.modelc.ready.then((m) => m.received).then(() => %s)' % drive)
            except (RuntimeError, OSError, ValueError) as e:
                r = None
                notok('whole stream: drive', e)
            if r:
                v, p = r['view'], []
                want = ((49 * 8 + 64) % 4096, (-5 * 8) % 4096, round(65536 * 1.1), 16)
                got = (v['yaw'], v['pitch'], v['zoom'], v['error'])
                if got != want:
                    p.append('view %s, expected %s' % (got, want))
                for f in r['moving']:
                    if f['error'] != 32 or not f['moving']:
                        p.append('a moving frame at bound %d (moving %s), expected 32' % (f['error'], f['moving']))
                if r['rest']['error'] != 16 or r['rest']['moving']:
                    p.append('the frame at rest at bound %d (moving %s), expected 16' % (r['rest']['error'], r['rest']['moving']))
                view_args = ['--yaw', str(v['yaw'] * 360 / 4096), '--pitch', str(v['pitch'] * 360 / 4096),
                             '--zoom', str(v['zoom'] / 65536)]
                p += frame_against(r, native.depth(levels, view_args, 'driven'),
                                   'the native viewer at that view')
                check('whole stream: drag, wheel and key reach the view (yaw %d pitch %d zoom %d), coarse frames '
                      'while moving, the fine frame equals the native viewer\'s' % got[:3], p)

        # ---- cuts: the deepest complete level, and the truncation shown ----
        rnd = random.Random(args.seed)
        fixed = {0, 10, MC_HEADER - 1, MC_HEADER, total - 1} | {e + k for e in da for k in (-1, 0)}
        chosen = {rnd.randrange(MC_HEADER + 1, da[0] - 1)}   # within the palette and the first levels
        while len(chosen) < 4:
            chosen.add(rnd.randrange(da[0] + 1, total - 1))
        chosen -= fixed
        cuts = sorted(fixed | chosen)
        good = []
        for k in cuts:
            d = depth_at(k)
            tag = 'cut at byte %d' % k
            r = load(tag, '/cut/%d.mcs' % k)
            if not r:
                continue
            s, p = r['state'], []
            err = s['error'] or {}
            if not s['done'] or s['ok'] or err.get('name') != 'truncated' or err.get('at') != k:
                p.append('error %s, expected truncated at byte %d' % (json.dumps(s['error']), k))
            if s['depth'] != d:
                p.append('depth %d, expected %d' % (s['depth'], d))
            kept = 'drawing depth %d, the last complete level' % d if d else 'nothing was drawable'
            line = 'stream: truncated at byte %d; %s' % (k, kept)
            if r['status'].split('\n')[-1] != line:
                p.append('status %r, expected its last line %r' % (r['status'], line))
            if d:
                p += frame_against(r, native.depth(d), 'the native viewer at --depth %d' % d)
            else:
                if r['frames'] or r['frame'] is not None:
                    p.append('%d frames drawn with nothing drawable' % r['frames'])
                p += blank(r)
            if p:
                notok(tag + ' (depth %d)' % d, p)
            else:
                good.append('%d:%d' % (k, d))
        check('%d cuts (in the header, at each drawable_at and a byte before, a byte before the end, %d at random '
              'with seed %d): each shows "truncated at byte k" and draws its deepest complete level exactly as '
              'the native viewer at that --depth, or nothing when none is complete [byte:depth %s]' %
              (len(cuts), len(chosen), args.seed, ' '.join(good)),
              [] if len(good) == len(cuts) else ['%d of %d cuts failed (above)' % (len(cuts) - len(good), len(cuts))])

        # ---- damaged: the error the native reader finds, the frame of the last good level ----
        def damaged(key, data, expect_name, expect_at, expect_depth, what):
            streams.data[key + '.mcs'] = data
            nrgb, nrc, _, nerr = native.stream(key, data)
            r = load(what, '/data/%s.mcs' % key)
            if not r:
                return
            s, p = r['state'], []
            err = s['error'] or {}
            if (err.get('name'), err.get('at')) != (expect_name, expect_at):
                p.append('error %s, expected %s at byte %d' % (json.dumps(s['error']), expect_name, expect_at))
            if s['depth'] != expect_depth:
                p.append('depth %d, expected %d' % (s['depth'], expect_depth))
            native_line = nerr.split('\n')[-1].split(': ', 1)[-1]
            if r['status'].split('\n')[-1] != native_line:
                p.append('status %r, the native viewer\'s %r' % (r['status'], native_line))
            if nrc != 1:
                p.append('the native viewer exited %d, expected 1' % nrc)
            if expect_depth:
                p += frame_against(r, nrgb, 'the native viewer of the same bytes (--stream)')
                p += frame_against(r, native.depth(expect_depth), 'the native viewer at --depth %d' % expect_depth)
            else:
                if r['frames']:
                    p.append('%d frames drawn with nothing drawable' % r['frames'])
                p += blank(r)
            check('%s: "%s", %s, as the native viewer%s' % (
                what, native_line, 'the last good level drawn' if expect_depth else 'no model drawn',
                ' and its --depth %d frame' % expect_depth if expect_depth else ''), p)

        for lv in (4, levels):   # a byte in the middle of level lv's record: its CRC fails
            at = (da[lv - 2] + da[lv - 1]) // 2
            data = bytearray(stream)
            data[at] ^= 0x55
            damaged('flip%d' % lv, bytes(data), 'crc', da[lv - 2], lv - 1,
                    'byte %d (level %d\'s record) flipped' % (at, lv))
        forged = bytearray(stream)   # version 4 under a valid header CRC
        forged[4:6] = struct.pack('<H', 4)
        forged[16:20] = struct.pack('<I', zlib.crc32(bytes(forged[:16])))
        damaged("version", bytes(forged), "version", 4, 0, "version 4 (header CRC valid)")
        raw = bytearray(stream)
        raw[4] ^= 0x03
        damaged('versionbyte', bytes(raw), 'crc', 0, 0, 'the version byte changed alone')
        damaged('trailing', stream + b'\0junk', 'trailing', total, levels, 'bytes after the end record')

        # ---- missing stream, file:// ----
        r = load('missing stream', '/web/missing.mcs')
        if r:
            line = 'stream: HTTP 404 for /web/missing.mcs; nothing was drawable'
            p = [] if r['status'] == line and not r['frames'] else ['status %r, %d frames' % (r['status'], r['frames'])]
            check('a stream the server does not have: "%s", no model drawn' % line, p + blank(r))
        try:
            v = page.eval('file://' + os.path.abspath(os.path.join(args.webdir, 'stream.html')),
                          "window.modelc.ready.then(() => 'loaded', () => document.getElementById('status').textContent)")
            check('from file://: the page says it needs http(s): "%s"' % v,
                  [] if isinstance(v, str) and 'needs http(s)' in v else ['status %r' % v])
        except (RuntimeError, OSError, ValueError) as e:
            notok('from file://', e)

        # ---- progressive: level by level with pauses; drawn while the fetch is still going ----
        pause = 300
        try:
            r = page.eval(page_url('/slow/%d.mcs' % pause), PROGRESS_JS, 30000)
        except (RuntimeError, OSError, ValueError) as e:
            r = None
            notok('progressive', e)
        if r:
            p, depths = [], []
            for shot in r['shots']:
                d = shot['frame']['model']
                depths.append('%d@%d' % (d, shot['state']['bytes']))
                if shot['state']['done']:
                    p.append('a shot after the end')
                if not shot['status'].split('\n')[-1].startswith('stream: depth %d of %d after ' % (d, levels)):
                    p.append('status %r at depth %d' % (shot['status'], d))
                if shot['state']['bytes'] >= total:
                    p.append('depth %d drawn only after all %d bytes' % (d, total))
                p += frame_against(shot, native.depth(d), 'the native viewer at --depth %d' % d)
            s = r['state']
            if len(r['shots']) < levels - 2:   # a level whose frame came late is passed over by the next
                p.append('%d levels drawn before the fetch ended (%s), expected at least %d' %
                         (len(r['shots']), ' '.join(depths), levels - 2))
            if not s['ok'] or s['depth'] != levels:
                p.append('state at the end %s' % json.dumps(s))
            if s['drawable'] and (s['drawable'][0]['depth'], s['drawable'][0]['bytes']) != (1, da[0]):
                p.append('first drawable %s, expected depth 1 at %d bytes' % (s['drawable'][0], da[0]))
            check('progressive (a %d ms pause after each level): each level drawn while the fetch went on, '
                  'equal to the native viewer at its depth [depth@bytes %s of %d]; the first picture after %d '
                  'bytes (%.1f %%)' % (pause, ' '.join(depths), total, da[0], 100.0 * da[0] / total), p)
        print('# %d requests in %.1f s' % (len(streams.requests), time.time() - t0), flush=True)
    except (RuntimeError, OSError, ValueError) as e:
        notok('chromium session', e)
    finally:
        b.close()
        server.shutdown()
    return 1 if failed else 0


MC_HEADER = 20   # stream.h MC_STREAM_HEADER_BYTES

if __name__ == '__main__':
    sys.exit(main())
