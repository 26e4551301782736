// Play/pause, the time slider, playback speed and the clock. The replay shows the
// recorded frames (the CSV's communication points); playing runs a clock at `speed`
// times real time and shows the last frame at or before it.
export class Playback {
  constructor(time, onFrame) {
    this.time = time;
    this.onFrame = onFrame;
    this.frame = 0;
    this.clock = time[0];
    this.speed = 1;
    this.playing = false;
    this.play = document.getElementById('play');
    this.slider = document.getElementById('time');
    this.speedSelect = document.getElementById('speed');
    this.readout = document.getElementById('clock');
    this.slider.max = String(time.length - 1);
    this.play.addEventListener('click', () => this.toggle());
    // scrubbing holds the replay still at the chosen frame
    this.slider.addEventListener('input', () => {
      this.setPlaying(false);
      this.show(Number(this.slider.value));
    });
    this.speedSelect.addEventListener('change', () => { this.speed = Number(this.speedSelect.value); });
    window.addEventListener('keydown', event => {
      if (event.target instanceof HTMLSelectElement) return;
      if (event.code === 'Space') { event.preventDefault(); this.toggle(); }
      else if (event.code === 'ArrowRight') { this.setPlaying(false); this.show(this.frame + 1); }
      else if (event.code === 'ArrowLeft') { this.setPlaying(false); this.show(this.frame - 1); }
    });
  }

  toggle() {
    // play at the last frame starts over
    if (!this.playing && this.frame === this.time.length - 1) this.show(0);
    this.setPlaying(!this.playing);
  }

  setPlaying(playing) {
    this.playing = playing;
    this.play.textContent = playing ? 'Pause' : 'Play';
  }

  // Shows frame i (clamped) and sets the clock to its time.
  show(i) {
    this.frame = Math.min(Math.max(i, 0), this.time.length - 1);
    this.clock = this.time[this.frame];
    this.slider.value = String(this.frame);
    const end = this.time[this.time.length - 1];
    this.readout.textContent = `t = ${this.clock.toFixed(3)} s / ${end.toFixed(3)} s`;
    this.onFrame(this.frame);
  }

  // Advances the clock by `seconds` of wall time while playing.
  advance(seconds) {
    if (!this.playing) return;
    this.clock += seconds * this.speed;
    let i = this.frame;
    while (i + 1 < this.time.length && this.time[i + 1] <= this.clock) ++i;
    const clock = this.clock;
    if (i !== this.frame) this.show(i);
    this.clock = clock;  // show() snaps to the frame's time; the clock runs on between frames
    if (i === this.time.length - 1) this.setPlaying(false);
  }
}
