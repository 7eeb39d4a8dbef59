//! What takes or makes each endpoint's messages: the role part of the endpoints' rows
//! ([`endpoint_list`]), read here, above the input handlers and the output producers, as
//! [`role`]. The DDS set-up subscribes every input with its handler and publishes every output
//! with its producer; the live view's inputs reach the same handlers.

use super::endpoints::{endpoint_list, Endpoint};
use super::inputs::{self, InputContext, InputHandler};
use super::outputs::{self, OutputProducer};

/// What takes or makes an endpoint's messages.
#[derive(Clone, Copy)]
pub(crate) enum Role {
    /// Its own code: the services (`services.rs`), `/diagnostics` (`diagnostics.rs`), `/rosout`
    /// (the client library), the recording's own channels (`record.rs`).
    Own,
    /// An input topic's handler.
    Input(&'static dyn InputHandler),
    /// An output made by the publisher thread from each tick's output.
    Output(&'static dyn OutputProducer),
}

const fn own() -> Role {
    Role::Own
}

const fn input(handler: &'static dyn InputHandler) -> Role {
    Role::Input(handler)
}

const fn output(producer: &'static dyn OutputProducer) -> Role {
    Role::Output(producer)
}

/// Declares [`role`] from the rows' roles.
macro_rules! roles {
    ($($(#[doc = $doc:literal])* $(#[cfg($cfg:meta)])* $variant:ident: $row:expr => $role:expr,)*) => {
        /// The role of `e`, as its row says.
        pub(crate) fn role(e: Endpoint) -> Role {
            match e {
                $($(#[cfg($cfg)])* Endpoint::$variant => $role,)*
            }
        }
    };
}

endpoint_list!(roles);

/// A live-view client's message on the `k`-th instance of input `endpoint` (CDR, or JSON when
/// `json`): handled by the endpoint's handler.
pub(crate) fn on_payload(
    cx: &InputContext<'_>,
    endpoint: Endpoint,
    k: usize,
    json: bool,
    payload: &[u8],
) {
    if let Role::Input(handler) = role(endpoint) {
        handler.on_payload(cx, endpoint, k, json, payload)
    }
}
