// For the README's picture of the web viewer (make readme-images, through tests/web/cdp.py --eval-file):
// drags the model for about two seconds through the page's own handlers, so that the engine has
// compiled the module's hot code and the status line shows a frame time the page really reaches,
// ends turned 25 degrees and seen from a little above, and rests on a fine frame; its value is that
// frame's figures.
(async () => {
  const m = await window.modelc.ready;
  const canvas = document.getElementById('view');
  const pointer = (type, x, y, buttons) => canvas.dispatchEvent(new PointerEvent(type, {
    clientX: x, clientY: y, pointerId: 1, isPrimary: true, pointerType: 'mouse', buttons: buttons, bubbles: true }));
  const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  pointer('pointerdown', 100, 100, 1);
  for (let i = 1; i <= 60; i++) {   // out and back, then to +36 px (288 units) and -14 px (-112 units)
    const out = Math.round(200 * Math.sin(i / 60 * Math.PI));
    pointer('pointermove', 100 + out + Math.round(36 * i / 60), 100 - Math.round(14 * i / 60), 1);
    await sleep(30);
  }
  pointer('pointerup', 136, 86, 0);
  return m.idle();
})()
