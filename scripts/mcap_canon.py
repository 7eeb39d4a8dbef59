"""mcap_canon.py FILE.mcap...: writes FILE.mcap.canon — the file's header, schemas, channels, every
message (channel, times, sequence, sha256 of the data), metadata and attachments, in file order —
and removes the .mcap. Masked: the run's wall-clock start time. Not compared: the chunk layout
(where the writer thread cut chunks depends on its timing)."""
import sys, os, hashlib
from mcap.stream_reader import StreamReader
from mcap.records import Metadata, Header, Schema, Channel, Message, Attachment, Chunk
from mcap.reader import make_reader
def canon(p, lines):
    with open(p, 'rb') as f:
        r = make_reader(f)
        h = r.get_header(); lines.append(f"Header {h.profile!r} {h.library!r}")
        summ = r.get_summary()
        for sid, s in sorted(summ.schemas.items()):
            lines.append(f"Schema {sid} {s.name} {s.encoding} {hashlib.sha256(s.data).hexdigest()}")
        for cid, c in sorted(summ.channels.items()):
            lines.append(f"Channel {cid} {c.topic} {c.schema_id} {c.message_encoding} {sorted(c.metadata.items())}")
        for sch, ch, m in r.iter_messages(log_time_order=False):
            lines.append(f"Message {ch.topic} {m.log_time} {m.publish_time} {m.sequence} {hashlib.sha256(m.data).hexdigest()}")
        for m in r.iter_metadata():
            md = dict(m.metadata)
            for k in ('start_time', 'start_time_ns'):
                if k in md: md[k] = 'MASKED'
            lines.append(f"Metadata {m.name} {sorted(md.items())!r}")
        for a in r.iter_attachments():
            lines.append(f"Attachment {a.name} {a.media_type} {hashlib.sha256(a.data).hexdigest()}")
        st = summ.statistics
        lines.append(f"Statistics {st.message_count} {st.schema_count} {st.channel_count} {st.metadata_count} {st.message_start_time} {st.message_end_time} {sorted(st.channel_message_counts.items())}")
for p in sys.argv[1:]:
    lines = []
    try:
        canon(p, lines)
    except Exception as e:
        lines.append(f"UNREADABLE {type(e).__name__}")
    with open(p + '.canon', 'w') as f:
        f.write('\n'.join(lines) + '\n')
    os.remove(p)
