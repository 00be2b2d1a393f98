#!/usr/bin/env python3
"""Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe: JSON
messages separated by NUL bytes on file descriptors 3 and 4), with nothing but the standard library.

    cdp.py URL [--size WxH] [--eval JS | --eval-file FILE] [--screenshot OUT.png]

Opens URL in real time (not virtual time, so performance.now() is the page's own clock), waits for
the load event, evaluates JS (awaiting it when it is a promise) and prints its value as JSON, then
writes a screenshot of the viewport. Exits non-zero with one line on any failure.
"""
import argparse
import base64
import fcntl
import json
import os
import subprocess
import sys
import tempfile


class Browser:
    def __init__(self, width, height):
        self.profile = tempfile.TemporaryDirectory(ignore_cleanup_errors=True)
        # every end above 4, so that moving two of them to 3 and 4 in the child cannot overwrite one
        def high(fd):
            moved = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 5)
            os.close(fd)
            return moved
        to_child_r, self.to_child = (high(fd) for fd in os.pipe())
        self.from_child, from_child_w = (high(fd) for fd in os.pipe())
        # the child reads commands on fd 3 and writes replies on fd 4 (subprocess closes other
        # descriptors only after preexec_fn, so 3 and 4 are kept by not closing any)
        def fds():
            os.dup2(to_child_r, 3, inheritable=True)
            os.dup2(from_child_w, 4, inheritable=True)
        self.proc = subprocess.Popen(
            ['chromium', '--headless', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--hide-scrollbars',
             '--remote-debugging-pipe', '--user-data-dir=' + self.profile.name, '--window-size=%d,%d' % (width, height),
             'about:blank'],
            preexec_fn=fds, close_fds=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child_r)
        os.close(from_child_w)
        self.buf = b''
        self.next_id = 0

    def send(self, method, params=None, session=None):
        self.next_id += 1
        msg = {'id': self.next_id, 'method': method, 'params': params or {}}
        if session:
            msg['sessionId'] = session
        os.write(self.to_child, json.dumps(msg).encode() + b'\0')
        return self.next_id

    def read(self):
        while b'\0' not in self.buf:
            chunk = os.read(self.from_child, 1 << 20)
            if not chunk:
                raise RuntimeError('chromium closed the pipe')
            self.buf += chunk
        msg, self.buf = self.buf.split(b'\0', 1)
        return json.loads(msg)

    def call(self, method, params=None, session=None):
        want = self.send(method, params, session)
        while True:
            msg = self.read()
            if msg.get('id') == want:
                if 'error' in msg:
                    raise RuntimeError('%s: %s' % (method, msg['error'].get('message')))
                return msg.get('result', {})

    def wait_event(self, name, session):
        while True:
            msg = self.read()
            if msg.get('method') == name and msg.get('sessionId') == session:
                return msg

    def close(self):
        try:
            self.send('Browser.close')
            self.proc.wait(timeout=10)
        except (OSError, subprocess.TimeoutExpired):
            self.proc.kill()
            self.proc.wait()
        self.profile.cleanup()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('url')
    ap.add_argument('--size', default='800x600')
    ap.add_argument('--eval')
    ap.add_argument('--eval-file')
    ap.add_argument('--screenshot')
    args = ap.parse_args()
    w, h = (int(v) for v in args.size.split('x'))
    if args.eval_file:
        with open(args.eval_file) as f:
            args.eval = f.read()
    b = Browser(w, h)
    try:
        target = b.call('Target.createTarget', {'url': 'about:blank'})['targetId']
        session = b.call('Target.attachToTarget', {'targetId': target, 'flatten': True})['sessionId']
        b.call('Page.enable', session=session)
        b.call('Emulation.setDeviceMetricsOverride', {'width': w, 'height': h, 'deviceScaleFactor': 1, 'mobile': False},
               session=session)
        b.call('Page.navigate', {'url': args.url}, session=session)
        b.wait_event('Page.loadEventFired', session)
        if args.eval:
            r = b.call('Runtime.evaluate', {'expression': args.eval, 'awaitPromise': True, 'returnByValue': True},
                       session=session)
            if 'exceptionDetails' in r:
                raise RuntimeError('the page threw: %s' % r['exceptionDetails'].get('exception', {}).get('description', r['exceptionDetails']))
            print(json.dumps(r.get('result', {}).get('value')))
        if args.screenshot:
            png = b.call('Page.captureScreenshot', {'format': 'png'}, session=session)['data']
            with open(args.screenshot + '.tmp', 'wb') as f:
                f.write(base64.b64decode(png))
            os.replace(args.screenshot + '.tmp', args.screenshot)
    except (RuntimeError, OSError, ValueError) as e:
        print('cdp.py: %s' % e, file=sys.stderr)
        return 1
    finally:
        b.close()
    return 0


if __name__ == '__main__':
    sys.exit(main())
