package io.etherware.examples.bench;

import com.fasterxml.jackson.databind.JavaType;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.pendulum.components.AnglesReading;
import io.etherware.pendulum.components.PendulumContents;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.function.Supplier;
import org.HdrHistogram.Histogram;

/**
 * Section 4: the XML codec's cost per message, encode and decode, for a Tick and for the
 * pendulum's Angles reading, beside Jackson JSON of the same message (the same fields in a flat
 * envelope, decoded back to an equal {@link Message}). For each: the mean ns/op over a timed
 * batch, the percentiles of single calls (each includes a {@code System.nanoTime()} pair, about
 * 20-30 ns) and the heap bytes allocated per call ({@code ThreadMXBean#getThreadAllocatedBytes}).
 * From the core module's codec harness. Runs on the caller's thread.
 */
final class CodecCost {

    static final String SECTION = "4. codec";
    private static final int WARMUP_ROUNDS = 3;
    private static final double ENCODE_AIM_NS = 3_000;
    private static final double DECODE_AIM_NS = 6_000;

    /** Keeps results alive so the JIT cannot drop the calls. */
    private static volatile long sink;

    /**
     * A message as flat JSON: the same fields as the XML document.
     *
     * @param <T> the contents' type
     */
    record JsonEnvelope<T extends Contents>(String profile, String sender, long timeStamp, Criticality criticality,
                                            long periodNs, long deadlineNs, long wcetNs, String messageId,
                                            T contents) {

        static <T extends Contents> JsonEnvelope<T> of(Message message, Class<T> type) {
            return new JsonEnvelope<>(message.profile().toString(), message.sender().toString(), message.timeStamp(),
                    message.qos().criticality(), message.qos().periodNs(), message.qos().deadlineNs(),
                    message.qos().wcetNs(), message.messageId().toString(), type.cast(message.contents()));
        }

        Message toMessage() {
            return new Message(Profile.parse(profile), Profile.parse(sender), timeStamp,
                    new QoS(criticality, periodNs, deadlineNs, wcetNs), contents, MessageId.parse(messageId), null);
        }
    }

    private final BenchConfig config;
    private final MessageCodec codec;
    private final ObjectMapper json = new ObjectMapper();

    CodecCost(BenchConfig config) {
        this.config = config;
        this.codec = MessageCodec.builder().contentsTypes(PendulumContents.register(new ContentsTypes())).build();
    }

    List<BenchRow> measure() {
        Message tick = new Message(Profile.parse("controller[car=1]"), Profile.parse("notifier"),
                1_732_233_600_000_000_000L, QoS.periodic(Criticality.HIGH, 15_000_000),
                new Tick(8_123_456_789L, 42, 15_000_000), new MessageId("node1", 1042), null);
        Message angles = new Message(Profile.parse("controller[car=1]"), Profile.parse("dsp-proxy[car=1]"),
                1_732_233_600_015_000_000L, new QoS(Criticality.HIGH, 15_000_000, 12_000_000, 2_000_000),
                new AnglesReading(1001, 77, -2048, 513, 15_015_000, -0.0314, 0.0125), new MessageId("node1", 3), null);
        for (int round = 0; round < WARMUP_ROUNDS; round++) {
            measureMessage(tick, Tick.class, "tick");
            measureMessage(angles, AnglesReading.class, "angles");
        }
        var rows = new ArrayList<BenchRow>();
        rows.addAll(measureMessage(tick, Tick.class, "tick"));
        rows.addAll(measureMessage(angles, AnglesReading.class, "angles"));
        return rows;
    }

    private <T extends Contents> List<BenchRow> measureMessage(Message message, Class<T> type, String name) {
        byte[] xml = codec.encode(message);
        if (!codec.decode(xml).equals(message)) {
            throw new IllegalStateException("XML round trip changed " + message);
        }
        JavaType envelopeType = json.getTypeFactory().constructParametricType(JsonEnvelope.class, type);
        JsonEnvelope<T> envelope = JsonEnvelope.of(message, type);
        byte[] jsonBytes = writeJson(envelope);
        if (!readJson(jsonBytes, envelopeType).toMessage().equals(message)) {
            throw new IllegalStateException("JSON round trip changed " + message);
        }
        String condition = name + " (" + xml.length + " B XML, " + jsonBytes.length + " B JSON)";
        BenchRow xmlEncode = row("codec.xml.encode." + name, "XML MessageCodec encode", condition,
                () -> codec.encode(message));
        BenchRow xmlDecode = row("codec.xml.decode." + name, "XML MessageCodec decode", condition,
                () -> codec.decode(xml));
        BenchRow jsonEncode = row("codec.json.encode." + name, "Jackson JSON encode", condition,
                () -> writeJson(JsonEnvelope.of(message, type)));
        BenchRow jsonDecode = row("codec.json.decode." + name, "Jackson JSON decode", condition,
                () -> readJson(jsonBytes, envelopeType).toMessage());
        return List.of(
                xmlEncode.judged("encode <= 3 us/op", xmlEncode.value() <= ENCODE_AIM_NS),
                jsonEncode,
                xmlDecode.judged("decode <= 6 us/op", xmlDecode.value() <= DECODE_AIM_NS),
                jsonDecode);
    }

    private byte[] writeJson(Object value) {
        try {
            return json.writeValueAsBytes(value);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private JsonEnvelope<?> readJson(byte[] bytes, JavaType type) {
        try {
            return json.readValue(bytes, type);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Mean over a batch, percentiles of single calls, bytes allocated per call. */
    private BenchRow row(String id, String variant, String condition, Supplier<Object> call) {
        int ops = config.codecOps();
        long batchStartNs = System.nanoTime();
        for (int i = 0; i < ops; i++) {
            sink += call.get().hashCode();
        }
        double meanNs = (System.nanoTime() - batchStartNs) / (double) ops;
        Histogram singleNs = Histograms.latencyNs();
        for (int i = 0; i < ops; i++) {
            long startNs = System.nanoTime();
            Object result = call.get();
            singleNs.recordValue(Histograms.clampNs(System.nanoTime() - startNs));
            sink += result.hashCode();
        }
        int allocationOps = Math.min(ops, 20_000);
        long allocatedBefore = Throughput.Allocation.currentThreadBytes();
        for (int i = 0; i < allocationOps; i++) {
            sink += call.get().hashCode();
        }
        double allocatedPerOp = (Throughput.Allocation.currentThreadBytes() - allocatedBefore) / (double) allocationOps;
        return new BenchRow(id, SECTION, variant, condition, "ns", Percentiles.of(singleNs), meanNs, "ns/op", true,
                "", "", String.format(Locale.ROOT, "%.0f B allocated/op; percentiles of single calls", allocatedPerOp));
    }
}
