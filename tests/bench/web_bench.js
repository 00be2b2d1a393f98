// Times the web viewer's module in the page it ships in (tests/bench/web.sh adds this script to a copy
// of the page): after a warm-up of at least a turn and 3 s (so the engine has compiled the hot code fully), F frames of a
// turn of yaw (frame i at i * 4096 / F, as the native viewer's --bench), drawn by mcw_draw as the
// page draws them (clear, render, finish, RGBA), in batches of B frames timed with performance.now();
// prints "MODELC-BENCH w h frames median_ms points" on the console: the median over batches of a
// batch's time over its frames.
'use strict';
(async function () {
  const m = await window.modelc.ready;
  const ex = m.exports();
  const canvas = document.getElementById('view');
  const w = canvas.width, h = canvas.height;
  const q = new URLSearchParams(location.search);
  const F = +(q.get('frames') || 200), B = 10, error = 16;
  const frame = (i) => ex.mcw_draw(w, h, Math.floor(i * 4096 / F), 0, 65536, error);
  // warm-up: Chromium compiles a module's hot functions fully only after they have run a while
  const warm = performance.now();
  for (let i = 0; i < F || performance.now() - warm < 3000; i++) frame(i % F);
  const ms = [];
  let points = 0;
  for (let i = 0; i < F; i += B) {
    const t0 = performance.now();
    for (let k = i; k < i + B && k < F; k++) { frame(k); points += ex.mcw_drawn(); }
    ms.push((performance.now() - t0) / Math.min(B, F - i));
  }
  ms.sort((a, b) => a - b);
  const mid = ms.length >> 1;
  const median = ms.length % 2 ? ms[mid] : (ms[mid - 1] + ms[mid]) / 2;
  console.log('MODELC-BENCH ' + w + ' ' + h + ' ' + F + ' ' + median.toFixed(4) + ' ' + Math.round(points / F));
})();
