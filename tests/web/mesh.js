// Drives the web viewer's mesh modes through its own key handler (tests/web/suite.sh evaluates this
// in a page opened with ?mode=...&lod=..., through tests/web/cdp.py): the frame the address asks
// for, then m (the next mode) and [ (half the splits above the base mesh), then an arrow key; each
// frame at rest read back from the canvas as base64 RGBA with the view and level it was drawn at.
(async () => {
  const m = await window.modelc.ready;
  const canvas = document.getElementById('view');
  const grab = (rest) => {
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    let bin = '';
    for (let i = 0; i < data.length; i += 8192) bin += String.fromCharCode.apply(null, data.subarray(i, i + 8192));
    return { rest: rest, view: m.view(), rgba: btoa(bin) };
  };
  const key = (k) => window.dispatchEvent(new KeyboardEvent('keydown', { key: k, bubbles: true, cancelable: true }));
  const frames = [grab(await m.idle())];
  key('m');
  key('[');
  frames.push(grab(await m.idle()));
  key('ArrowRight');
  frames.push(grab(await m.idle()));
  return { width: canvas.width, height: canvas.height, help: document.getElementById('help').textContent, frames: frames };
})()
