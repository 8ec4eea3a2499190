//! The force command as a PWM duty cycle, over any `embedded-hal` [`SetDutyCycle`]
//! channel. The firmware's `board` build drives TIM3's channel 1 with it
//! (`firmware/src/pwm.rs`; `host-sim/tests/qemu_pwm.rs` reads the compare register back in
//! QEMU).

use super::ForceActuator;
use embedded_hal::pwm::SetDutyCycle;

/// A force command as a PWM duty cycle: `duty = force / full_scale_n` of the channel's
/// maximum, rounded to nearest and clamped to `[0, max]` (for example a
/// current-controlled motor whose stall force is `full_scale_n` at full duty).
#[derive(Debug)]
pub struct PwmForce<P> {
    pwm: P,
    full_scale_n: f32,
}

impl<P: SetDutyCycle> PwmForce<P> {
    /// Wraps a PWM channel whose full duty gives `full_scale_n` \[N\] (`> 0`; a non-positive
    /// or non-finite value is read as 1 N).
    pub fn new(pwm: P, full_scale_n: f32) -> Self {
        let full_scale_n = if full_scale_n > 0.0 && full_scale_n.is_finite() {
            full_scale_n
        } else {
            1.0
        };
        Self { pwm, full_scale_n }
    }

    /// The channel back.
    pub fn release(self) -> P {
        self.pwm
    }
}

/// The duty cycle that commands `force_n` [N] on a channel whose full duty `max` gives
/// `full_scale_n`. A NaN force gives 0.
fn duty(force_n: f32, full_scale_n: f32, max: u16) -> u16 {
    let frac = (force_n / full_scale_n).clamp(0.0, 1.0);
    // `frac` is in [0, 1] (NaN clamps to NaN and casts to 0), so the product fits u16.
    let duty = (frac * f32::from(max) + 0.5) as u16;
    duty.min(max)
}

impl<P: SetDutyCycle> ForceActuator for PwmForce<P> {
    fn set_force_n(&mut self, force_n: f32) {
        let duty = duty(force_n, self.full_scale_n, self.pwm.max_duty_cycle());
        // A PWM error cannot be reported from here; the next tick sets the duty again.
        let _ = self.pwm.set_duty_cycle(duty);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::convert::Infallible;

    /// A channel that remembers its last duty.
    struct Channel {
        max: u16,
        duty: u16,
    }

    impl embedded_hal::pwm::ErrorType for Channel {
        type Error = Infallible;
    }

    impl SetDutyCycle for Channel {
        fn max_duty_cycle(&self) -> u16 {
            self.max
        }
        fn set_duty_cycle(&mut self, duty: u16) -> Result<(), Infallible> {
            self.duty = duty;
            Ok(())
        }
    }

    #[test]
    fn the_duty_is_the_force_over_full_scale_rounded_and_clamped() {
        let mut pwm = PwmForce::new(Channel { max: 800, duty: 1 }, 20.0);
        for (force_n, duty) in [
            (0.0, 0),
            (10.0, 400),
            (20.0, 800),
            (25.0, 800),
            (-1.0, 0),
            (f32::NAN, 0),
            (0.0124, 0),
            (0.0126, 1),
            (3.33, 133),
        ] {
            pwm.set_force_n(force_n);
            assert_eq!(pwm.pwm.duty, duty, "{force_n} N");
        }
        assert_eq!(duty(19.99, 20.0, u16::MAX), 65502);
    }

    #[test]
    fn a_bad_full_scale_is_read_as_one_newton() {
        for bad in [0.0, -3.0, f32::NAN, f32::INFINITY] {
            let pwm = PwmForce::new(Channel { max: 100, duty: 0 }, bad);
            assert_eq!(pwm.full_scale_n, 1.0);
            assert_eq!(pwm.release().max, 100);
        }
    }
}
