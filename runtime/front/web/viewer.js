// The web viewer: loads NAME.wasm (web.c: the runtime and the bake, no imports), draws its frames
// into the canvas, turns the model with the mouse, zooms with the wheel, and takes the terminal
// viewer's keys. While the view moves it draws at twice the level-of-detail bound (coarse), and at
// rest one frame at the bound (fine), as the terminal viewer does.
//
// The view is kept in the runtime's integers (angles in 4096 units a turn, zoom in Q16), so a test
// can ask the native viewer for exactly the same frame (tests/web). window.modelc exposes the state
// for tests and for the curious.
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
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  const image = ctx.createImageData(w, h);

  const view = { yaw: 0, pitch: 0, zoom: ZOOM_ONE, error: LOD_PIXEL };
  let ex = null, depth = 0, moving = false, dragging = null, pending = false, restTimer = 0;
  let frames = 0, last = null;
  const idleWaiters = [];

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

  function draw() {
    pending = false;
    const error = moving ? 2 * view.error : view.error;
    const t0 = performance.now();
    const rc = ex.mcw_draw(w, h, view.yaw, view.pitch, view.zoom, error);
    const ms = performance.now() - t0;
    if (rc !== 0) {
      status.textContent = name + ': mcw_draw returned ' + rc;
      return;
    }
    image.data.set(new Uint8ClampedArray(ex.memory.buffer, ex.mcw_rgba(), w * h * 4));
    ctx.putImageData(image, 0, 0);
    frames++;
    last = { yaw: view.yaw, pitch: view.pitch, zoom: view.zoom, error: error, moving: moving,
             depth: ex.mcw_drawn_depth(), points: ex.mcw_drawn(), ms: ms };
    status.textContent = name + ' | depth ' + last.depth + '/' + depth + ' | ' +
      last.points.toLocaleString('en') + ' points | ' + ms.toFixed(2) + ' ms | zoom ' +
      (view.zoom / ZOOM_ONE).toFixed(2) + ' | ' + (moving ? 'coarse' : 'fine') + ' | ' + w + 'x' + h;
    if (!moving) while (idleWaiters.length) idleWaiters.shift()(last);
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
      default: return;
    }
    e.preventDefault();
    nudge();
  });

  const ready = instantiate().then((instance) => {
    ex = instance.exports;
    depth = ex.mcw_depth();
    if (w > ex.mcw_max_width() || h > ex.mcw_max_height())
      throw new Error('the canvas is larger than the bake\'s screen ' + ex.mcw_max_width() + 'x' + ex.mcw_max_height());
    request();
    return window.modelc;
  }).catch((err) => {
    status.textContent = name + ': ' + err.message;
    throw err;
  });

  window.modelc = {
    ready: ready,
    view: () => Object.assign({}, view),
    frames: () => frames,
    last: () => last,
    exports: () => ex,   // the module's own functions (web.c), for benchmarks
    // resolves with the next fine frame (at rest), drawn after everything so far
    idle: () => new Promise((resolve) => { idleWaiters.push(resolve); if (!moving) request(); }),
  };
})();
