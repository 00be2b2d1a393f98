// The web viewer: loads NAME.wasm (web.c: the runtime and the bake, no imports), draws its frames
// into the canvas, turns the model with the mouse, zooms with the wheel, and takes the terminal
// viewer's keys. While the view moves it draws at twice the level-of-detail bound (coarse), and at
// rest one frame at the bound (fine), as the terminal viewer does.
//
// The view is kept in the runtime's integers (angles in 4096 units a turn, zoom in Q16), so a test
// can ask the native viewer for exactly the same frame (tests/web). window.modelc exposes the state
// for tests and for the curious.
//
// A bake with a mesh part (--as both) has the terminal viewer's mesh modes: m cycles points, shaded,
// lines and shaded+lines, [ and ] halve or double the splits above the base mesh (the level of
// detail, in vertices); ?mode=lines&lod=N in the address starts there. A mesh frame is drawn at the
// chosen level whether the view moves or rests (web.c mcw_draw_mesh: the native viewer's
// --mode STYLE --lod N). On the stream page the mesh's modes come with its base mesh, each level is
// drawn as its splits come (the level asked for, clamped to those), and the line styles draw shaded
// until the adjacency has come, as the native viewer's --stream.
//
// The stream page (stream.html: <body data-stream="NAME.mcs">, or ?stream=URL) loads NAME-stream.wasm,
// which holds no model, and fetches the stream (modelc --emit stream) through response.body, feeding
// each piece to the module as it arrives: the deepest complete level is drawn as soon as it is
// checked, and again whenever a deeper one is; the status line tells the stream's state, and a
// truncated or damaged stream its error, while the last good level stays drawn. http(s) only.
'use strict';
(function () {
  const ANGLE_FULL = 4096, ZOOM_ONE = 65536, LOD_PIXEL = 16;
  const ZOOM_MIN = ZOOM_ONE / 64, ZOOM_MAX = ZOOM_ONE * 64;
  const ZOOM_STEP = 1.1;     // a wheel notch or a + / - press, as the terminal viewer's key
  const DRAG_UNITS = 8;      // angle units a pixel of drag: 320 pixels turn 225 degrees
  const KEY_UNITS = 64;      // angle units an arrow press: 5.6 degrees
  const REST_MS = 150;       // after the last key or wheel event, the fine frame

  const canvas = document.getElementById('view');
  const status = document.getElementById('status');
  const name = document.body.dataset.model;
  const streaming = document.body.dataset.stream !== undefined;
  const streamUrl = streaming ? (new URLSearchParams(location.search).get('stream') || document.body.dataset.stream) : null;
  const help = document.getElementById('help');
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  const image = ctx.createImageData(w, h);

  const MODES = ['points', 'shaded', 'lines', 'shaded+lines'];
  const params = new URLSearchParams(location.search);
  const view = { yaw: 0, pitch: 0, zoom: ZOOM_ONE, error: LOD_PIXEL, mode: 0, level: 0 };
  let meshVertices = 0, meshBase = 0, meshCap = 0;   // the mesh part (0: none); the levels that have come
  let ex = null, depth = 0, moving = false, dragging = null, pending = false, restTimer = 0;
  let frames = 0, last = null;
  const idleWaiters = [];
  // the stream's state: bytes come from the network, total and levels (D) from its header, drawable
  // the bytes and time at which each depth became drawable, error the reader's or the network's
  const st = { url: streamUrl, bytes: 0, total: 0, levels: 0, depth: 0, done: false, ok: false,
               error: null, drawable: [], meshLevel: 0, meshLines: 0, meshRefused: 0 };
  let frameLine = '', streamLine = '';

  // file:// pages cannot fetch, so NAME.wasm.js carries the same bytes in base64 for them
  function loadScript(src) {
    return new Promise((resolve, reject) => {
      const s = document.createElement('script');
      s.src = src;
      s.onload = resolve;
      s.onerror = () => reject(new Error('cannot load ' + src));
      document.head.appendChild(s);
    });
  }
  async function instantiate() {
    if (streaming) {
      if (location.protocol !== 'http:' && location.protocol !== 'https:')
        throw new Error('the stream page needs http(s), as fetch cannot read file:// (open index.html, or serve this folder)');
      const r = await fetch(name + '-stream.wasm');
      if (!r.ok) throw new Error(name + '-stream.wasm: HTTP ' + r.status);
      return (await WebAssembly.instantiate(await r.arrayBuffer(), {})).instance;
    }
    if (location.protocol === 'http:' || location.protocol === 'https:') {
      const r = await fetch(name + '.wasm');
      if (!r.ok) throw new Error(name + '.wasm: HTTP ' + r.status);
      return (await WebAssembly.instantiate(await r.arrayBuffer(), {})).instance;
    }
    await loadScript(name + '.wasm.js');
    const text = atob(window.MODELC_WASM_BASE64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
    return (await WebAssembly.instantiate(bytes, {})).instance;
  }

  const mod = (a) => ((a % ANGLE_FULL) + ANGLE_FULL) % ANGLE_FULL;
  function zoomBy(f) { view.zoom = Math.min(ZOOM_MAX, Math.max(ZOOM_MIN, Math.round(view.zoom * f))); }

  function showStatus() {
    status.textContent = streaming ? (frameLine ? frameLine + '\n' : '') + streamLine : frameLine;
  }
  function draw() {
    pending = false;
    if (streaming && (view.mode ? meshCap === 0 : depth === 0)) {   // nothing drawable (yet): no frame
      if (!moving) while (idleWaiters.length) idleWaiters.shift()(null);
      return;
    }
    const error = moving ? 2 * view.error : view.error;
    const t0 = performance.now();
    const rc = view.mode ? ex.mcw_draw_mesh(w, h, view.yaw, view.pitch, view.zoom, view.mode, view.level)
                         : ex.mcw_draw(w, h, view.yaw, view.pitch, view.zoom, error);
    const ms = performance.now() - t0;
    if (rc !== 0) {
      frameLine = name + ': ' + (view.mode ? 'mcw_draw_mesh' : 'mcw_draw') + ' returned ' + rc;
      showStatus();
      return;
    }
    image.data.set(new Uint8ClampedArray(ex.memory.buffer, ex.mcw_rgba(), w * h * 4));
    ctx.putImageData(image, 0, 0);
    frames++;
    const tail = ms.toFixed(2) + ' ms | zoom ' + (view.zoom / ZOOM_ONE).toFixed(2) + ' | ';
    if (view.mode) {
      last = { yaw: view.yaw, pitch: view.pitch, zoom: view.zoom, moving: moving, mode: MODES[view.mode],
               level: ex.mcw_mesh_level(), faces: ex.mcw_mesh_faces(), drawn: ex.mcw_mesh_drawn(),
               linePixels: ex.mcw_mesh_line_pixels(), ms: ms };
      last.shadedOnly = view.mode !== 1 && !ex.mcw_mesh_lines_ready();
      frameLine = name + ' | ' + last.mode + (last.shadedOnly ? ' (shaded: no adjacency yet)' : '') +
        ' | level ' + last.level + '/' + meshVertices + ', ' +
        last.faces.toLocaleString('en') + ' faces | ' + (view.mode === 2 ? last.linePixels.toLocaleString('en') +
        ' line pixels' : last.drawn.toLocaleString('en') + ' drawn') + ' | ' + tail + w + 'x' + h;
    } else {
      last = { yaw: view.yaw, pitch: view.pitch, zoom: view.zoom, error: error, moving: moving, mode: 'points',
               depth: ex.mcw_drawn_depth(), points: ex.mcw_drawn(), ms: ms, model: depth };
      frameLine = name + ' | depth ' + last.depth + '/' + depth + ' | ' +
        last.points.toLocaleString('en') + ' points | ' + tail + (moving ? 'coarse' : 'fine') + ' | ' + w + 'x' + h;
    }
    showStatus();
    if (!moving) while (idleWaiters.length) idleWaiters.shift()(last);
  }
  // the mesh part once the module has one (a bake's at once, a stream's when its base has come): the
  // mode and level the address asks for, the keys in the help line
  function meshSetup() {
    meshVertices = ex.mcw_mesh_vertices();
    if (!meshVertices) return;
    meshBase = ex.mcw_mesh_base_vertices();
    meshCap = ex.mcw_mesh_cap();
    const mode = MODES.indexOf(params.get('mode') || 'points'), lod = Number(params.get('lod'));
    view.mode = mode > 0 ? mode : 0;
    view.level = params.get('lod') && Number.isInteger(lod) ? Math.min(meshVertices, Math.max(meshBase, lod)) : meshVertices;
    if (help) help.textContent += ' · m: points / shaded / lines / shaded+lines · [ ] level of detail';
  }
  function request() {
    if (pending || !ex) return;
    pending = true;
    requestAnimationFrame(draw);
  }
  // a key or wheel event moves the view now and rests REST_MS after the last one
  function nudge() {
    moving = true;
    clearTimeout(restTimer);
    restTimer = setTimeout(() => { if (!dragging) { moving = false; request(); } }, REST_MS);
    request();
  }

  canvas.addEventListener('pointerdown', (e) => {
    dragging = { x: e.clientX, y: e.clientY };
    moving = true;
    try { canvas.setPointerCapture(e.pointerId); } catch (err) { /* synthetic pointers have none */ }
    canvas.focus();
    request();
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!dragging) return;
    view.yaw = mod(view.yaw + (e.clientX - dragging.x) * DRAG_UNITS);
    view.pitch = mod(view.pitch + (e.clientY - dragging.y) * DRAG_UNITS);
    dragging = { x: e.clientX, y: e.clientY };
    request();
  });
  function release() {
    if (!dragging) return;
    dragging = null;
    moving = false;
    request();
  }
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    zoomBy(e.deltaY < 0 ? ZOOM_STEP : 1 / ZOOM_STEP);
    nudge();
  }, { passive: false });
  window.addEventListener('keydown', (e) => {
    switch (e.key) {
      case 'ArrowRight': view.yaw = mod(view.yaw + KEY_UNITS); break;
      case 'ArrowLeft': view.yaw = mod(view.yaw - KEY_UNITS); break;
      case 'ArrowDown': view.pitch = mod(view.pitch + KEY_UNITS); break;
      case 'ArrowUp': view.pitch = mod(view.pitch - KEY_UNITS); break;
      case '+': case '=': zoomBy(ZOOM_STEP); break;
      case '-': case '_': zoomBy(1 / ZOOM_STEP); break;
      case 'r': case 'R': view.yaw = 0; view.pitch = 0; view.zoom = ZOOM_ONE; break;
      case 'm': case 'M': if (meshVertices) view.mode = (view.mode + 1) % MODES.length; break;
      case '[': case ']': {   // half or twice the splits above the base mesh, as the terminal viewer
        if (!meshVertices) return;
        const splits = Math.min(view.level, meshCap) - meshBase;
        const want = e.key === '[' ? Math.floor(splits / 2) : splits ? splits * 2 : 1;
        view.level = want > meshVertices - meshBase ? meshVertices : meshBase + want;
        break;
      }
      default: return;
    }
    e.preventDefault();
    nudge();
  });

  // ---- the stream page: fetch, feed, draw each level as it completes ----
  function streamStatus() {
    const kept = st.depth ? 'drawing depth ' + st.depth + ', the last complete level' : 'nothing was drawable';
    if (st.error && st.error.at !== undefined)
      streamLine = 'stream: ' + st.error.name + ' at byte ' + st.error.at + '; ' + kept;
    else if (st.error)
      streamLine = 'stream: ' + st.error.message + '; ' + kept;
    else if (st.done)
      streamLine = 'stream: complete, depth ' + st.depth + ', ' + st.bytes + ' bytes';
    else
      streamLine = 'stream: depth ' + st.depth + ' of ' + (st.levels || '?') + ' after ' + st.bytes + ' of ' +
        (st.total || '?') + ' bytes';
    if (meshVertices)
      streamLine += ' | mesh level ' + meshCap + ' of ' + meshVertices + (ex.mcw_mesh_lines_ready() ? '' : ', no lines yet');
    else if (st.meshRefused)
      streamLine += ' | its mesh (' + st.meshRefused + ' vertices) is larger than this page\'s mesh memory: points only';
    showStatus();
  }
  function readerState() {
    st.total = ex.mcw_stream_total();
    st.levels = ex.mcw_stream_levels();
    const rc = ex.mcw_stream_error();
    if (rc !== 0 && !st.error) {
      const at = ex.mcw_stream_error_name(rc);
      const bytes = new Uint8Array(ex.memory.buffer, at);
      let n = 0;
      while (bytes[n]) n++;
      st.error = { name: String.fromCharCode.apply(null, bytes.subarray(0, n)), code: rc, at: ex.mcw_stream_error_at() };
    }
    const d = ex.mcw_depth();
    if (d > depth) {
      depth = st.depth = d;
      st.drawable.push({ depth: d, bytes: st.bytes, ms: Math.round(performance.now()) });
      request();
    }
    if (!meshVertices) meshSetup();
    if (!meshVertices) st.meshRefused = ex.mcw_mesh_refused();
    const cap = meshVertices ? ex.mcw_mesh_cap() : 0, lines = meshVertices ? ex.mcw_mesh_lines_ready() : 0;
    if (cap !== st.meshLevel || lines !== st.meshLines) {
      meshCap = st.meshLevel = cap;
      st.meshLines = lines;
      if (view.mode) request();
    }
  }
  // a piece of the body into the module, a scratch area at a time; false once the reader stopped
  function feed(bytes) {
    const room = ex.mcw_scratch_bytes();
    for (let i = 0; i < bytes.length; i += room) {
      const piece = bytes.subarray(i, Math.min(bytes.length, i + room));
      new Uint8Array(ex.memory.buffer, ex.mcw_scratch(), piece.length).set(piece);
      st.bytes += piece.length;
      const rc = ex.mcw_feed(piece.length);
      readerState();
      if (rc !== 0) return false;
    }
    return true;
  }
  async function receive() {
    streamStatus();
    try {
      const r = await fetch(streamUrl, { cache: 'no-store' });
      if (!r.ok) throw new Error('HTTP ' + r.status + ' for ' + streamUrl);
      const body = r.body.getReader();
      for (;;) {
        let piece;
        try {
          piece = await body.read();
        } catch (err) {
          throw new Error('read failed after ' + st.bytes + ' bytes: ' + err.message);
        }
        if (piece.done) {
          ex.mcw_end();
          readerState();
          break;
        }
        if (!feed(piece.value)) {
          body.cancel().catch(() => {});
          break;
        }
        streamStatus();
      }
    } catch (err) {
      if (!st.error) st.error = { name: 'fetch', message: err.message };
    }
    st.done = true;
    st.ok = !st.error;
    streamStatus();
    request();
    return snapshot();
  }
  function snapshot() {
    return Object.assign({}, st, { error: st.error && Object.assign({}, st.error), drawable: st.drawable.slice() });
  }

  const ready = instantiate().then((instance) => {
    ex = instance.exports;
    depth = ex.mcw_depth();
    meshSetup();
    if (w > ex.mcw_max_width() || h > ex.mcw_max_height())
      throw new Error('the canvas is larger than the bake\'s screen ' + ex.mcw_max_width() + 'x' + ex.mcw_max_height());
    request();
    return window.modelc;
  }).catch((err) => {
    status.textContent = name + ': ' + err.message;
    throw err;
  });
  // the stream page: resolves with the stream's state once it ended, complete or not
  const received = streaming ? ready.then(receive) : Promise.resolve(null);
  received.catch(() => {});

  window.modelc = {
    ready: ready,
    view: () => Object.assign({}, view, { mode: MODES[view.mode] }),
    frames: () => frames,
    last: () => last,
    exports: () => ex,   // the module's own functions (web.c), for benchmarks
    stream: () => (streaming ? snapshot() : null),   // the stream's state (the stream page)
    received: received,
    // resolves with the next fine frame (at rest), drawn after everything so far (null on the stream
    // page while nothing is drawable)
    idle: () => new Promise((resolve) => { idleWaiters.push(resolve); if (!moving) request(); }),
  };
})();
