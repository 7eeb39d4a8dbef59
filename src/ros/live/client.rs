//! One client's connection, on a thread of its own: the handshake (either subprotocol name),
//! then a loop that reads what the client sends and writes what its queue holds. The socket is
//! non-blocking after the handshake, so a slow client only fills its own queue.
//!
//! What the client sends is checked here: a frame that is not the protocol (not JSON, an
//! unknown op or opcode, more than [`MAX_FRAME_BYTES`]) ends the connection with a log line;
//! a mistake within the protocol (an unknown channel, a topic the node does not take) is
//! answered with a `status` message and the connection kept.

use super::hub::Hub;
use super::protocol::{self, ClientBinary, ClientOp, FrameError, Level};
use super::queue::{Client, Frame, CLIENT_QUEUE};
use super::request::{Answer, Request};
use crate::ros::endpoints::{Endpoint, Service};
use std::collections::HashMap;
use std::io::ErrorKind;
use std::net::TcpStream;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;
use tungstenite::handshake::server::{ErrorResponse, Request as HttpRequest, Response};
use tungstenite::protocol::WebSocketConfig;
use tungstenite::{Error as WsError, Message, WebSocket};

/// Largest frame (and message) a client may send, bytes; a larger one ends its connection.
pub(crate) const MAX_FRAME_BYTES: usize = 1 << 20;
/// Longest the handshake may take (a client that connects and sends nothing is let go).
const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(2);
/// How long the loop waits for an outgoing frame before it looks at the socket again: the
/// latency of what a client sends.
const POLL: Duration = Duration::from_millis(2);
/// Frames read before the loop turns to writing.
const READS_PER_TURN: usize = 256;
/// Bytes of written frames the socket has not taken yet, at most; beyond, the queue holds them.
const MAX_WRITE_BUFFER: usize = 4 << 20;

/// Why a connection ended.
enum End {
    /// The client closed it, or the node is stopping.
    Closed,
    /// The client sent what the protocol does not allow (logged).
    Kicked(String),
    /// The socket failed.
    Failed(String),
}

impl End {
    /// The client kicked for a frame outside the protocol.
    fn kicked(e: FrameError) -> Self {
        End::Kicked(e.to_string())
    }
}

/// Serves one accepted connection until it ends.
pub(crate) fn serve(stream: TcpStream, hub: Arc<Hub>) {
    let addr = match stream.peer_addr() {
        Ok(a) => a,
        Err(_) => return,
    };
    let Some(mut ws) = handshake(stream) else {
        hub.stats.refused.fetch_add(1, Ordering::Relaxed);
        return;
    };
    let (tx, rx) = mpsc::sync_channel(CLIENT_QUEUE);
    let client = hub.add(tx);
    log(
        &hub,
        "live_client",
        false,
        format!("live view: client {addr} connected"),
    );
    let mut conn = Connection {
        hub: hub.clone(),
        client: client.clone(),
        channels: HashMap::new(),
    };
    let end = conn.run(&mut ws, &rx);
    hub.remove(&client);
    // The answer to a client's close frame, which tungstenite has queued.
    let _ = ws.flush();
    match end {
        End::Closed => log(
            &hub,
            "live_client",
            false,
            format!("live view: client {addr} left"),
        ),
        End::Kicked(why) => {
            hub.stats.kicked.fetch_add(1, Ordering::Relaxed);
            let _ = ws.close(None);
            let _ = ws.flush();
            log(
                &hub,
                "live_kicked",
                true,
                format!("live view: client {addr} disconnected: it sent {why}"),
            )
        }
        End::Failed(e) => log(
            &hub,
            "live_client",
            false,
            format!("live view: client {addr}: {e}"),
        ),
    }
}

/// A log line by the executor (rate-limited per `key` there).
fn log(hub: &Hub, key: &'static str, warn: bool, line: String) {
    hub.request(Request::Log { key, warn, line });
}

/// The WebSocket handshake, answering with the subprotocol the client offered; `None` when it
/// offered neither of ours (HTTP 400), timed out or was not a WebSocket request.
fn handshake(stream: TcpStream) -> Option<WebSocket<TcpStream>> {
    stream.set_read_timeout(Some(HANDSHAKE_TIMEOUT)).ok()?;
    stream.set_write_timeout(Some(HANDSHAKE_TIMEOUT)).ok()?;
    let _ = stream.set_nodelay(true);
    let config = WebSocketConfig::default()
        .max_message_size(Some(MAX_FRAME_BYTES))
        .max_frame_size(Some(MAX_FRAME_BYTES))
        .max_write_buffer_size(MAX_WRITE_BUFFER);
    // The error type is tungstenite's (an HTTP response), whatever its size.
    #[allow(clippy::result_large_err)]
    let callback = |req: &HttpRequest, mut resp: Response| -> Result<Response, ErrorResponse> {
        let offered = req
            .headers()
            .get_all("sec-websocket-protocol")
            .iter()
            .filter_map(|h| h.to_str().ok());
        match protocol::choose_subprotocol(offered) {
            Some(p) => {
                resp.headers_mut().insert(
                    "sec-websocket-protocol",
                    tungstenite::http::HeaderValue::from_static(p),
                );
                Ok(resp)
            }
            None => {
                let mut e = ErrorResponse::new(Some(format!(
                    "expected a Sec-WebSocket-Protocol of {}",
                    protocol::SUBPROTOCOLS.join(" or ")
                )));
                *e.status_mut() = tungstenite::http::StatusCode::BAD_REQUEST;
                Err(e)
            }
        }
    };
    let ws = tungstenite::accept_hdr_with_config(stream, callback, Some(config)).ok()?;
    ws.get_ref().set_nonblocking(true).ok()?;
    Some(ws)
}

/// A connection's own state: the client's channels (its id → input topic, instance and
/// encoding).
struct Connection {
    hub: Arc<Hub>,
    client: Arc<Client>,
    channels: HashMap<u32, (Endpoint, usize, bool)>,
}

impl Connection {
    fn status(&self, level: Level, msg: &str, id: Option<&str>) {
        self.client.send(
            Frame::Text(protocol::status(level, msg, id)),
            &self.hub.stats,
        );
    }

    /// The greeting, then reads and writes until the connection ends.
    fn run(&mut self, ws: &mut WebSocket<TcpStream>, rx: &Receiver<Frame>) -> End {
        for text in [
            self.hub.server_info.clone(),
            self.hub.catalogue.advertise_json(),
            self.hub.catalogue.services_json.clone(),
        ] {
            self.client.send(Frame::Text(text), &self.hub.stats);
        }
        let mut held: Option<Message> = None;
        loop {
            if self.hub.stopping.load(Ordering::Relaxed) {
                return End::Closed;
            }
            if let Err(end) = self.read_all(ws) {
                return end;
            }
            if let Err(e) = write_queued(ws, rx, &mut held) {
                return e;
            }
            if held.is_none() {
                match rx.recv_timeout(POLL) {
                    Ok(f) => held = Some(f.into_message()),
                    Err(RecvTimeoutError::Timeout) => {}
                    Err(RecvTimeoutError::Disconnected) => return End::Closed,
                }
            } else {
                // The socket is full: wait for the client to read.
                std::thread::sleep(POLL);
            }
        }
    }

    /// What the client has sent so far, at most [`READS_PER_TURN`] frames (then the loop
    /// writes before it reads on: a client that floods is still sent its answers).
    fn read_all(&mut self, ws: &mut WebSocket<TcpStream>) -> Result<(), End> {
        for _ in 0..READS_PER_TURN {
            match ws.read() {
                Ok(Message::Text(t)) => self.on_text(t.as_str()).map_err(End::kicked)?,
                Ok(Message::Binary(b)) => self.on_binary(&b).map_err(End::kicked)?,
                Ok(Message::Close(_)) => return Err(End::Closed),
                Ok(_) => {}
                Err(WsError::Io(e)) if e.kind() == ErrorKind::WouldBlock => return Ok(()),
                Err(WsError::ConnectionClosed | WsError::AlreadyClosed) => return Err(End::Closed),
                Err(WsError::Capacity(e)) => {
                    return Err(End::Kicked(format!(
                        "a frame over the {MAX_FRAME_BYTES}-byte limit ({e})"
                    )))
                }
                Err(WsError::Protocol(e)) => {
                    return Err(End::Kicked(format!("a frame that breaks WebSocket ({e})")))
                }
                Err(e) => return Err(End::Failed(e.to_string())),
            }
        }
        Ok(())
    }

    fn on_text(&mut self, text: &str) -> Result<(), FrameError> {
        match ClientOp::parse(text)? {
            ClientOp::Subscribe { subscriptions } => {
                for s in subscriptions {
                    match self.hub.catalogue.channel(s.channel_id) {
                        Some(ch) => {
                            if !self.hub.subscribe(&self.client, s.id, ch.outlet) {
                                self.status(
                                    Level::Error,
                                    &format!("subscription id {} is already in use", s.id),
                                    None,
                                );
                            }
                        }
                        None => self.status(
                            Level::Warning,
                            &format!("no channel with id {}", s.channel_id),
                            None,
                        ),
                    }
                }
            }
            ClientOp::Unsubscribe { subscription_ids } => {
                for s in subscription_ids {
                    self.hub.unsubscribe(&self.client, s);
                }
            }
            ClientOp::Advertise { channels } => {
                for c in channels {
                    let json = match c.encoding.as_str() {
                        "json" => true,
                        "cdr" => false,
                        other => {
                            self.status(
                                Level::Error,
                                &format!(
                                    "encoding {} is not supported (cdr or json)",
                                    muscle_actuator_core::text::excerpt(other)
                                ),
                                None,
                            );
                            continue;
                        }
                    };
                    match self.hub.catalogue.input(&c.topic, &c.schema_name) {
                        Ok((endpoint, k)) => {
                            self.channels.insert(c.id, (endpoint, k, json));
                        }
                        Err(e) => self.status(Level::Error, &e.to_string(), None),
                    }
                }
            }
            ClientOp::Unadvertise { channel_ids } => {
                for id in channel_ids {
                    self.channels.remove(&id);
                }
            }
            ClientOp::GetParameters {
                parameter_names,
                id,
            } => self.ask(Request::GetParameters {
                names: parameter_names,
                id,
                answer: self.answer(),
            }),
            ClientOp::SetParameters { parameters, id } => self.ask(Request::SetParameters {
                parameters,
                id,
                answer: self.answer(),
            }),
            ClientOp::SubscribeParameterUpdates {}
            | ClientOp::UnsubscribeParameterUpdates {}
            | ClientOp::SubscribeConnectionGraph {}
            | ClientOp::UnsubscribeConnectionGraph {}
            | ClientOp::FetchAsset {} => self.status(
                Level::Error,
                "this server does not offer that capability (see serverInfo)",
                None,
            ),
        }
        Ok(())
    }

    fn on_binary(&mut self, bytes: &[u8]) -> Result<(), FrameError> {
        match ClientBinary::parse(bytes)? {
            ClientBinary::MessageData {
                channel_id,
                payload,
            } => match self.channels.get(&channel_id) {
                Some(&(endpoint, k, json)) => self.ask(Request::Input {
                    endpoint,
                    k,
                    json,
                    payload: payload.to_vec(),
                }),
                None => self.status(
                    Level::Error,
                    &format!("no client channel with id {channel_id} was advertised"),
                    None,
                ),
            },
            ClientBinary::ServiceCall {
                service_id,
                call_id,
                encoding,
                payload,
            } => {
                let fail = |m: &str| {
                    self.client.send(
                        Frame::Text(protocol::service_failure(service_id, call_id, m)),
                        &self.hub.stats,
                    );
                };
                match Service::from_id(service_id) {
                    None => fail(&format!("no service with id {service_id}")),
                    Some(_) if encoding != "cdr" => fail(&format!(
                        "encoding {} is not supported (cdr)",
                        muscle_actuator_core::text::excerpt(encoding)
                    )),
                    Some(service) => self.ask(Request::Call {
                        service,
                        call_id,
                        payload: payload.to_vec(),
                        answer: self.answer(),
                    }),
                }
            }
        }
        Ok(())
    }

    fn answer(&self) -> Answer {
        Answer {
            client: self.client.clone(),
            stats: self.hub.stats.clone(),
        }
    }

    /// A request for the executor; when its queue is full the client is told so.
    fn ask(&self, r: Request) {
        if !self.hub.request(r) {
            self.status(
                Level::Warning,
                "the node is busy: request dropped, ask again",
                None,
            );
        }
    }
}

/// Writes what is held and what the queue has, until the socket stops taking frames.
fn write_queued(
    ws: &mut WebSocket<TcpStream>,
    rx: &Receiver<Frame>,
    held: &mut Option<Message>,
) -> Result<(), End> {
    loop {
        let m = match held.take() {
            Some(m) => m,
            None => match rx.try_recv() {
                Ok(f) => f.into_message(),
                Err(_) => break,
            },
        };
        match ws.write(m) {
            Ok(()) => {}
            Err(WsError::WriteBufferFull(m)) => {
                *held = Some(*m);
                break;
            }
            Err(WsError::Io(e)) if e.kind() == ErrorKind::WouldBlock => break,
            Err(WsError::ConnectionClosed | WsError::AlreadyClosed) => return Err(End::Closed),
            Err(e) => return Err(End::Failed(e.to_string())),
        }
    }
    match ws.flush() {
        Ok(()) => Ok(()),
        Err(WsError::Io(e)) if e.kind() == ErrorKind::WouldBlock => Ok(()),
        Err(WsError::ConnectionClosed | WsError::AlreadyClosed) => Err(End::Closed),
        Err(e) => Err(End::Failed(e.to_string())),
    }
}
