#!/usr/bin/env python3
"""What the web tests check of a module: wasm_info.py MODULE.wasm prints 'imports N', 'exports
NAME...' (sorted) and 'bytes N', read from the binary's import and export sections."""
import sys


def uleb(b, i):
    v = s = 0
    while True:
        x = b[i]
        i += 1
        v |= (x & 0x7f) << s
        s += 7
        if x < 0x80:
            return v, i


def sections(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\0asm\x01\0\0\0':
        sys.exit(path + ': not a wasm module')
    i, imports, exports = 8, 0, []
    while i < len(data):
        sid = data[i]
        size, j = uleb(data, i + 1)
        body = data[j:j + size]
        if sid == 2:
            imports = uleb(body, 0)[0]
        if sid == 7:
            n, k = uleb(body, 0)
            for _ in range(n):
                ln, k = uleb(body, k)
                exports.append(body[k:k + ln].decode())
                k += ln + 1
                _, k = uleb(body, k)
        i = j + size
    return imports, sorted(exports), len(data)


if __name__ == '__main__':
    imports, exports, size = sections(sys.argv[1])
    print('imports', imports)
    print('exports', ' '.join(exports))
    print('bytes', size)
