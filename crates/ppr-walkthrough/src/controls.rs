//! The keys: what each one does, decided apart from the window so it is tested.

use winit::keyboard::KeyCode;

use crate::fly_camera::MoveKeys;

/// What a key press asks for (movement keys are held, the others act once on press).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    ToggleHoles,
    ToggleFiltering,
    ToggleAntiBleeding,
    /// Blur the reflections of reflectors with roughness (glossy) or show them as mirrors.
    ToggleGlossy,
    /// Feed the previous frame's composite to PPR as its colour input.
    TogglePreviousFrame,
    NextView,
    NextCamera,
    /// Lose the GPU device on purpose, to see the recovery.
    LoseDevice,
    Quit,
}

/// The one-shot action of `key`, if any.
pub fn action(key: KeyCode) -> Option<Action> {
    Some(match key {
        KeyCode::KeyH => Action::ToggleHoles,
        KeyCode::KeyF => Action::ToggleFiltering,
        KeyCode::KeyB => Action::ToggleAntiBleeding,
        KeyCode::KeyG => Action::ToggleGlossy,
        KeyCode::KeyP => Action::TogglePreviousFrame,
        KeyCode::KeyV => Action::NextView,
        KeyCode::KeyC => Action::NextCamera,
        KeyCode::F9 => Action::LoseDevice,
        KeyCode::Escape => Action::Quit,
        _ => return None,
    })
}

/// Updates the held movement keys; returns whether `key` is one of them.
pub fn update_move_keys(keys: &mut MoveKeys, key: KeyCode, pressed: bool) -> bool {
    let slot = match key {
        KeyCode::KeyW | KeyCode::ArrowUp => &mut keys.forward,
        KeyCode::KeyS | KeyCode::ArrowDown => &mut keys.back,
        KeyCode::KeyA | KeyCode::ArrowLeft => &mut keys.left,
        KeyCode::KeyD | KeyCode::ArrowRight => &mut keys.right,
        KeyCode::KeyE | KeyCode::Space => &mut keys.up,
        KeyCode::KeyQ | KeyCode::ControlLeft => &mut keys.down,
        KeyCode::ShiftLeft | KeyCode::ShiftRight => &mut keys.fast,
        _ => return false,
    };
    *slot = pressed;
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toggles_and_movement_keys() {
        assert_eq!(action(KeyCode::KeyH), Some(Action::ToggleHoles));
        assert_eq!(action(KeyCode::KeyB), Some(Action::ToggleAntiBleeding));
        assert_eq!(action(KeyCode::KeyP), Some(Action::TogglePreviousFrame));
        assert_eq!(action(KeyCode::KeyG), Some(Action::ToggleGlossy));
        assert_eq!(action(KeyCode::KeyW), None);
        let mut keys = MoveKeys::default();
        assert!(update_move_keys(&mut keys, KeyCode::KeyW, true));
        assert!(update_move_keys(&mut keys, KeyCode::KeyQ, true));
        assert!(keys.forward && keys.down);
        assert!(update_move_keys(&mut keys, KeyCode::KeyW, false));
        assert!(!keys.forward);
        assert!(!update_move_keys(&mut keys, KeyCode::KeyH, true));
    }
}
