// The example pages' test picture, drawn with a 2D canvas (used by main.mjs and screenshot.mjs).

// A recognisable picture (drawn on a 320x240 grid, scaled to width x height): SMPTE-like colour
// bars, a grey ramp, a checker and some text.
export function drawTestPicture(width = 320, height = 240) {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const g = canvas.getContext('2d');
  g.scale(width / 320, height / 240);
  const bars = ['#c0c0c0', '#c0c000', '#00c0c0', '#00c000', '#c000c0', '#c00000', '#0000c0'];
  bars.forEach((c, i) => { g.fillStyle = c; g.fillRect((i * 320) / 7, 0, 320 / 7 + 1, 120); });
  for (let x = 0; x < 320; ++x) {  // grey ramp
    const v = Math.round((x / 319) * 255);
    g.fillStyle = `rgb(${v},${v},${v})`;
    g.fillRect(x, 120, 1, 30);
  }
  for (let y = 150; y < 240; y += 10)  // checker
    for (let x = 0; x < 160; x += 10) {
      g.fillStyle = ((x + y) / 10) % 2 ? '#fff' : '#000';
      g.fillRect(x, y, 10, 10);
    }
  g.fillStyle = '#102040';
  g.fillRect(160, 150, 160, 90);
  g.fillStyle = '#ffd040';
  g.font = 'bold 24px monospace';
  g.textAlign = 'center';
  g.fillText('crtforge', 240, 185);
  g.font = '14px monospace';
  g.fillStyle = '#80ff80';
  g.fillText('PRESS START', 240, 215);
  g.strokeStyle = '#fff';
  g.beginPath();
  g.arc(160, 75, 40, 0, 2 * Math.PI);
  g.stroke();
  return canvas;
}
