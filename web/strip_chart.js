// A small scrolling line chart on a canvas: the last SAMPLES samples of a few series,
// y range fitted to the samples visible now (so it follows the data: a past spike leaves
// the axis once it scrolls out), optionally on a log10 scale (residuals span decades).
// A value that is not finite is a gap, never an axis bound.

const SAMPLES = 300;
const LOG_FLOOR = 1e-18;

export class StripChart {
  constructor(parent, title, { log = false, unit = '' } = {}) {
    this.log = log;
    this.unit = unit;
    const box = document.createElement('div');
    box.className = 'plot';
    const heading = document.createElement('h3');
    heading.textContent = title;
    this.canvas = document.createElement('canvas');
    this.legend = document.createElement('div');
    this.legend.className = 'legend';
    box.append(heading, this.canvas, this.legend);
    parent.append(box);
    this.setSeries([]);
  }

  // series: [{label, color}]; clears the history (a new robot or constraint set).
  setSeries(series) {
    this.series = series.map((s) => ({ ...s, data: new Float64Array(SAMPLES).fill(NaN) }));
    this.head = 0;
    this.drawn = null;
    this.legend.replaceChildren(
      ...series.map((s) => {
        const span = document.createElement('span');
        span.style.color = s.color;
        span.textContent = `■ ${s.label}`;
        return span;
      }),
    );
    if (!series.length) this.legend.textContent = 'nothing to show';
  }

  // Keeps the series, forgets their history.
  clear() {
    for (const s of this.series) s.data.fill(NaN);
    this.head = 0;
    this.drawn = null;
  }

  // One value per series (NaN or an infinity leaves a gap).
  push(values) {
    for (let i = 0; i < this.series.length; i++) {
      const v = values[i];
      this.series[i].data[this.head] = !Number.isFinite(v) ? NaN : this.log ? Math.log10(Math.max(Math.abs(v), LOG_FLOOR)) : v;
    }
    this.head = (this.head + 1) % SAMPLES;
  }

  draw() {
    const { canvas } = this;
    const ratio = window.devicePixelRatio || 1;
    const width = Math.round(canvas.clientWidth * ratio);
    const height = Math.round(canvas.clientHeight * ratio);
    if (!width || !height) return;
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const ctx = canvas.getContext('2d');
    ctx.clearRect(0, 0, width, height);
    this.drawn = null;

    let lo = Infinity;
    let hi = -Infinity;
    let samples = 0;
    for (const s of this.series) {
      let n = 0;
      for (const v of s.data) {
        if (v < lo) lo = v;
        if (v > hi) hi = v;
        if (!Number.isNaN(v)) n++;
      }
      samples = Math.max(samples, n);
    }
    if (!(lo <= hi)) return;
    // What the axis spans and how many samples it shows (achdDemo.state().plots).
    this.drawn = { lo, hi, samples };
    // A flat line still needs a visible band around it. Halves keep hi - lo finite for
    // values near the largest doubles.
    const half = hi / 2 - lo / 2;
    const pad = half > 0 ? 0.16 * half : Math.max(Math.abs(hi) * 0.1, this.log ? 0.5 : 1e-9);
    lo -= pad;
    hi += pad;
    const range = hi / 2 - lo / 2;

    const left = 58 * ratio;
    const plotW = width - left - 4 * ratio;
    const y = (v) => 4 * ratio + (1 - (v / 2 - lo / 2) / range) * (height - 8 * ratio);
    ctx.font = `${10 * ratio}px ui-monospace, monospace`;
    ctx.fillStyle = '#5d6677';
    ctx.textBaseline = 'middle';
    ctx.fillText(this.label(hi - pad), 2, y(hi - pad));
    ctx.fillText(this.label(lo + pad), 2, y(lo + pad));
    ctx.strokeStyle = '#dde1e8';
    ctx.lineWidth = ratio;
    ctx.strokeRect(left, 0.5, plotW, height - 1);
    if (lo < 0 && hi > 0 && !this.log) {
      ctx.beginPath();
      ctx.moveTo(left, y(0));
      ctx.lineTo(left + plotW, y(0));
      ctx.stroke();
    }

    ctx.lineWidth = 1.5 * ratio;
    for (const s of this.series) {
      ctx.strokeStyle = s.color;
      ctx.beginPath();
      let pen = false;
      for (let k = 0; k < SAMPLES; k++) {
        const v = s.data[(this.head + k) % SAMPLES];
        if (Number.isNaN(v)) {
          pen = false;
          continue;
        }
        const px = left + (k / (SAMPLES - 1)) * plotW;
        if (pen) ctx.lineTo(px, y(v));
        else ctx.moveTo(px, y(v));
        pen = true;
      }
      ctx.stroke();
    }
  }

  label(v) {
    if (this.log) return `1e${Math.round(v)}`;
    const text = Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-2 && v !== 0) ? v.toExponential(1) : v.toPrecision(3);
    return this.unit ? `${text} ${this.unit}` : text;
  }
}
