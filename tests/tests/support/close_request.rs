//! Closing a window as a window manager's close button does, for the window tests (included
//! with `#[path]`: x11-dl is a dev-dependency, so the library half of pom-tests, which the
//! fuzz targets build, stays without it).

use pom_tests::xvfb::Xvfb;

/// Sends `window` the `WM_DELETE_WINDOW` message a window manager sends when its close button
/// is pressed (xdotool has no command for it: `windowclose` destroys the window instead).
pub fn request_close(xvfb: &Xvfb, window: x11_dl::xlib::Window) {
    use std::ffi::{CString, c_long};
    use x11_dl::xlib;
    let x = xlib::Xlib::open().expect("libX11 (Xvfb's own dependency)");
    let name = CString::new(format!(":{}", xvfb.display)).unwrap();
    // SAFETY: the display is checked before use and closed once; the event is a client
    // message laid out as Xlib defines it.
    unsafe {
        let display = (x.XOpenDisplay)(name.as_ptr());
        assert!(!display.is_null(), "cannot open display :{}", xvfb.display);
        let protocols = (x.XInternAtom)(display, c"WM_PROTOCOLS".as_ptr(), xlib::False);
        let delete = (x.XInternAtom)(display, c"WM_DELETE_WINDOW".as_ptr(), xlib::False);
        let mut data = xlib::ClientMessageData::new();
        data.set_long(0, delete as c_long);
        data.set_long(1, xlib::CurrentTime as c_long);
        let mut event = xlib::XEvent {
            client_message: xlib::XClientMessageEvent {
                type_: xlib::ClientMessage,
                serial: 0,
                send_event: xlib::True,
                display,
                window,
                message_type: protocols,
                format: 32,
                data,
            },
        };
        let sent = (x.XSendEvent)(display, window, xlib::False, xlib::NoEventMask, &mut event);
        assert_ne!(sent, 0, "XSendEvent failed");
        (x.XFlush)(display);
        (x.XCloseDisplay)(display);
    }
}
