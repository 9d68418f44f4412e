package io.etherware.examples.bench;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import java.io.BufferedInputStream;
import java.io.BufferedOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.time.Duration;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import org.HdrHistogram.Histogram;

/**
 * Section 5: a request and its reply over loopback TCP through two NetworkMessengers (outside
 * node a to an echo component on node b and back: XML encoded and decoded at both ends, each
 * node's kernel and dispatcher in the path), beside a raw TCP ping-pong of the same bytes (4-byte
 * length frames, TCP_NODELAY) and two steps between them (the ping-pong with the messenger's two
 * extra thread hand-offs, then with the XML codec too). Round trips are back to back (closed
 * loop), so the percentiles are of round trips as they came; the four phases alternate over rounds
 * so that a change of load on a shared machine hits them alike. From the services module's
 * loopback harness. Runs on the caller's thread.
 */
final class Loopback {

    static final String SECTION = "5. loopback round trip";
    private static final int ROUNDS = 3;
    private static final Profile ECHO = Profile.of("bench-echo");
    private static final Text PAYLOAD = new Text("ping");
    private static final double ROUND_TRIP_AIM_US = 40;

    @FunctionalInterface
    private interface RoundTrip {
        void run() throws Exception;
    }

    private final BenchConfig config;

    Loopback(BenchConfig config) {
        this.config = config;
    }

    List<BenchRow> measure() throws Exception {
        Histogram messengerNs = Histograms.latencyNs();
        Histogram rawNs = Histograms.latencyNs();
        var codec = new MessageCodec(new io.etherware.core.message.ContentsTypes());
        try (var b = EtherwareNode.builder().nodeId("bench-b").build().start();
             var bNet = NetworkMessenger.start(b, NetworkConfig.builder().listen("127.0.0.1", 0).build());
             var a = EtherwareNode.builder().nodeId("bench-a").build().start();
             var aNet = NetworkMessenger.start(a, NetworkConfig.builder().peer(bNet.localAddress()).build())) {
            b.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
            if (!aNet.awaitResolvable(ECHO, Duration.ofSeconds(30))) {
                throw new IllegalStateException("b's echo was never announced to a");
            }
            QoS qos = QoS.of(Criticality.HIGH);
            long timeoutNs = TimeUnit.SECONDS.toNanos(10);
            RoundTrip throughMessengers = () -> a.requestBlocking(ECHO, PAYLOAD, qos, timeoutNs);
            // The same bytes as the messengers carry: a request and its reply as encoded on the wire.
            Message request = new Message(ECHO, a.profile(), a.clock().epochNanos(), qos, PAYLOAD,
                    new MessageId("bench-a", 123_456), null);
            Message reply = new Message(a.profile(), ECHO, b.clock().epochNanos(), qos, PAYLOAD,
                    new MessageId("bench-b", 654_321), request.messageId());
            byte[] requestXml = codec.encode(request);
            byte[] replyXml = codec.encode(reply);
            Histogram handOffNs = Histograms.latencyNs();
            Histogram handOffCodecNs = Histograms.latencyNs();
            try (var pingPong = new RawPingPong(requestXml, replyXml, null, null, false);
                 var handOffs = new RawPingPong(requestXml, replyXml, null, null, true);
                 var handOffsCodec = new RawPingPong(requestXml, replyXml, codec, request, true)) {
                int warmup = Math.max(1_000, config.roundTrips() / 3);
                repeat(warmup, throughMessengers, null);
                repeat(warmup, pingPong::roundTrip, null);
                repeat(warmup, handOffs::roundTrip, null);
                repeat(warmup, handOffsCodec::roundTrip, null);
                for (int round = 0; round < ROUNDS; round++) {
                    repeat(config.roundTrips() / ROUNDS, pingPong::roundTrip, rawNs);
                    repeat(config.roundTrips() / ROUNDS, handOffs::roundTrip, handOffNs);
                    repeat(config.roundTrips() / ROUNDS, handOffsCodec::roundTrip, handOffCodecNs);
                    repeat(config.roundTrips() / ROUNDS, throughMessengers, messengerNs);
                }
            }
            String bytes = String.format(Locale.ROOT, "request %d B, reply %d B of XML", requestXml.length,
                    replyXml.length);
            OneWay oneWay = noneAfterHigh(a, aNet, b);
            UnderLow twoLanes = highUnderLow(2, qos, timeoutNs);
            UnderLow oneLane = highUnderLow(1, qos, timeoutNs);
            BenchRow messenger = BenchRow.latency("loopback.messenger", SECTION, "NetworkMessenger request/reply",
                    "idle, back to back", "us", Percentiles.of(messengerNs), bytes + "; encode+decode at both ends");
            BenchRow raw = BenchRow.latency("loopback.raw", SECTION, "raw TCP ping-pong, same bytes",
                    "idle, back to back", "us", Percentiles.of(rawNs), bytes + "; no codec");
            BenchRow handOff = BenchRow.latency("loopback.raw.hand-offs", SECTION,
                    "raw TCP ping-pong with the messenger's two extra hand-offs", "idle, back to back", "us",
                    Percentiles.of(handOffNs), bytes + "; no codec; reader thread to a worker at the echo,"
                            + " reader thread to the caller at the requester: the messenger's threads, nothing else");
            BenchRow handOffCodec = BenchRow.latency("loopback.raw.hand-offs.codec", SECTION,
                    "raw TCP ping-pong, the two hand-offs and the XML codec", "idle, back to back", "us",
                    Percentiles.of(handOffCodecNs), "as the row above, with the request and the reply encoded and"
                            + " decoded by MessageCodec at both ends; what is left to the messenger is the kernel's");
            double p50Ratio = messenger.p50() / raw.p50();
            double p99Ratio = messenger.p99() / raw.p99();
            BenchRow rtIdle = BenchRow.latency("loopback.messenger.rt-idle", SECTION,
                    "NetworkMessenger HIGH request/reply, Table II nodes, two lanes", "idle, back to back", "us",
                    Percentiles.of(twoLanes.idleNs()), "requester at the HIGH dispatcher's priority: the baseline of"
                            + " the next two rows");
            BenchRow saturated = BenchRow.latency("loopback.messenger.high-under-low", SECTION,
                    "NetworkMessenger HIGH request/reply, Table II nodes, two lanes (default)",
                    "LOW 64 KiB messages saturate the same pair", "us", Percentiles.of(twoLanes.saturatedNs()),
                    "HIGH on a connection of its own; " + twoLanes.lowNote());
            BenchRow single = BenchRow.latency("loopback.messenger.high-under-low.one-lane", SECTION,
                    "NetworkMessenger HIGH request/reply, Table II nodes, one lane (lanes=1)",
                    "LOW 64 KiB messages saturate the same pair", "us", Percentiles.of(oneLane.saturatedNs()),
                    "HIGH overtakes LOW in the queues, not in the sockets (128 KiB LOW bound); " + oneLane.lowNote());
            return List.of(messenger.judged("p50 <= 40 us", messenger.p50() <= ROUND_TRIP_AIM_US), raw, handOff,
                    handOffCodec,
                    BenchRow.value("loopback.ratio.p50", SECTION, "NetworkMessenger / raw TCP, p50",
                            "idle, back to back", p50Ratio, "x", "same run, same CPU-latency state")
                            .judged("<= 1.3x", p50Ratio <= 1.3),
                    BenchRow.value("loopback.ratio.p99", SECTION, "NetworkMessenger / raw TCP, p99",
                            "idle, back to back", p99Ratio, "x", "same run, same CPU-latency state")
                            .judged("<= 1.5x", p99Ratio <= 1.5),
                    rtIdle, saturated.judged("p99 <= 2x idle p99", saturated.p99() <= 2 * rtIdle.p99()), single,
                    BenchRow.latency("loopback.one-way.high", SECTION, "NetworkMessenger HIGH message, one way",
                            "idle, then a NONE message", "us", Percentiles.of(oneWay.highNs()),
                            "send to the receiving component's start; lane 0"),
                    BenchRow.latency("loopback.one-way.none-after-high", SECTION,
                            "NetworkMessenger NONE message sent right after a HIGH one, one way", "idle", "us",
                            Percentiles.of(oneWay.noneNs()), "lane 1; goes once lane 0 settled the HIGH one (the"
                                    + " order across lanes): a SYNC, its acknowledgement, then lane 1's writer"));
        }
    }

    private static final Profile MARKS = Profile.of("bench-marks");

    /** One-way times of a HIGH message and of a NONE message sent right after it, in ns. */
    private record OneWay(Histogram highNs, Histogram noneNs) {
    }

    /**
     * Pairs of messages from a to a component of b, one at a time: a HIGH one, and a NONE one
     * right after it, which by the order across lanes goes on lane 1 only once lane 0 settled the
     * HIGH one. Each is timed from its send to the start of its handling (one clock: both nodes
     * are in this JVM).
     */
    private OneWay noneAfterHigh(EtherwareNode a, NetworkMessenger aNet, EtherwareNode b) throws Exception {
        var arrivedNs = new java.util.concurrent.atomic.AtomicLongArray(2);
        b.add(MARKS, () -> (message, context) -> arrivedNs.set(
                message.qos().criticality() == Criticality.NONE ? 1 : 0, System.nanoTime()));
        if (!aNet.awaitResolvable(MARKS, Duration.ofSeconds(30))) {
            throw new IllegalStateException("b's " + MARKS + " was never announced to a");
        }
        Histogram highNs = Histograms.latencyNs();
        Histogram noneNs = Histograms.latencyNs();
        int count = Math.max(500, config.roundTrips() / 3);
        QoS high = QoS.of(Criticality.HIGH);
        long endNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30); // bounded if each takes long
        for (int i = -count / 4; i < count && System.nanoTime() - endNs < 0; i++) {
            arrivedNs.set(0, 0);
            arrivedNs.set(1, 0);
            long sentNs = System.nanoTime();
            a.send(MARKS, PAYLOAD, high);
            a.send(MARKS, PAYLOAD, QoS.NONE);
            while ((arrivedNs.get(0) == 0 || arrivedNs.get(1) == 0) && System.nanoTime() - endNs < 0) {
                java.util.concurrent.locks.LockSupport.parkNanos(10_000);
            }
            if (i >= 0 && arrivedNs.get(1) != 0) {
                highNs.recordValue(Histograms.clampNs(arrivedNs.get(0) - sentNs));
                noneNs.recordValue(Histograms.clampNs(arrivedNs.get(1) - sentNs));
            }
        }
        return new OneWay(highNs, noneNs);
    }

    private static final Profile SINK = Profile.of("bench-sink");
    private static final Text LOW_PAYLOAD = new Text("x".repeat(64 * 1024));

    /**
     * HIGH round trips while a sender thread floods the same pair of nodes with LOW 64 KiB messages
     * (as fast as a's queue to b takes them: the rest are shed, counted), between two more nodes
     * with the real-time scheduler (Table II) whose messengers run {@code lanes} lanes. The
     * requests are made from a thread at the HIGH dispatcher's priority, as a HIGH component's
     * would be; the flood thread is an ordinary one. Bounded by the number of round trips measured.
     */
    /**
     * @param idleNs      round trips on the same nodes from the same thread before the flood
     * @param saturatedNs round trips during the flood
     * @param lowBytes    LOW bytes the sink received during the flood
     * @param floodNs     how long the flood ran
     */
    private record UnderLow(Histogram idleNs, Histogram saturatedNs, long lowBytes, long floodNs) {
        String lowNote() {
            double mibPerS = lowBytes / (1024.0 * 1024.0) / (floodNs / 1e9);
            return String.format(Locale.ROOT, "LOW delivered meanwhile: %.0f MiB/s", mibPerS);
        }
    }

    private UnderLow highUnderLow(int lanes, QoS qos, long timeoutNs) throws Exception {
        try (var b = EtherwareNode.builder().nodeId("bench-b" + lanes).scheduler(config::realtimeScheduler)
                     .build().start();
             var bNet = NetworkMessenger.start(b, NetworkConfig.builder().lanes(lanes).listen("127.0.0.1", 0).build());
             var a = EtherwareNode.builder().nodeId("bench-a" + lanes).scheduler(config::realtimeScheduler)
                     .build().start();
             var aNet = NetworkMessenger.start(a, NetworkConfig.builder().lanes(lanes).peer(bNet.localAddress()).build())) {
            b.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
            var lowBytes = new java.util.concurrent.atomic.AtomicLong();
            b.add(SINK, () -> (message, context) -> lowBytes.addAndGet(LOW_PAYLOAD.text().length()));
            if (!aNet.awaitResolvable(ECHO, Duration.ofSeconds(30)) || !aNet.awaitResolvable(SINK, Duration.ofSeconds(30))) {
                throw new IllegalStateException("b" + lanes + "'s components were never announced to a" + lanes);
            }
            RoundTrip roundTrip = () -> a.requestBlocking(ECHO, PAYLOAD, qos, timeoutNs);
            Histogram idleNs = Histograms.latencyNs();
            Histogram saturatedNs = Histograms.latencyNs();
            long[] flood = new long[2];
            var failure = new java.util.concurrent.atomic.AtomicReference<Exception>();
            Thread requester = Thread.ofPlatform().name("bench-high-requester").start(() -> {
                Platform.current().configureCurrentThread(ThreadPolicy.fifo(ThreadSchedulingRule.HIGH_PRIORITY),
                        CpuSet.inherit());
                try {
                    repeat(Math.max(1_000, config.roundTrips() / 3), roundTrip, null);
                    repeat(Math.max(500, config.roundTrips() / 3), roundTrip, idleNs);
                    long fromBytes = lowBytes.get();
                    long fromNs = System.nanoTime();
                    underLowSaturation(a, roundTrip, saturatedNs);
                    flood[0] = lowBytes.get() - fromBytes;
                    flood[1] = System.nanoTime() - fromNs;
                } catch (Exception e) {
                    failure.set(e);
                }
            });
            requester.join();
            if (failure.get() != null) {
                throw failure.get();
            }
            return new UnderLow(idleNs, saturatedNs, flood[0], flood[1]);
        }
    }

    /** Records HIGH round trips into {@code saturatedNs} while a flood thread sends LOW to b's sink. */
    private void underLowSaturation(EtherwareNode a, RoundTrip highRoundTrip, Histogram saturatedNs)
            throws Exception {
        var flooding = new java.util.concurrent.atomic.AtomicBoolean(true);
        QoS low = QoS.of(Criticality.LOW);
        Thread flood = Thread.ofPlatform().daemon().name("bench-low-flood").start(() -> {
            while (flooding.get()) {
                try {
                    a.send(SINK, LOW_PAYLOAD, low);
                } catch (RuntimeException e) {
                    return; // the bench is closing
                }
                Thread.onSpinWait();
            }
        });
        try {
            Thread.sleep(200); // let the flood fill the queues and the socket
            int count = Math.max(500, config.roundTrips() / 3);
            long endNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30); // bounded if each takes long
            for (int i = 0; i < count && System.nanoTime() - endNs < 0; i++) {
                long startNs = System.nanoTime();
                highRoundTrip.run();
                saturatedNs.recordValue(Histograms.clampNs(System.nanoTime() - startNs));
            }
        } finally {
            flooding.set(false);
            flood.join(5_000);
        }
    }

    private static void repeat(int count, RoundTrip roundTrip, Histogram histogramNs) throws Exception {
        for (int i = 0; i < count; i++) {
            long startNs = System.nanoTime();
            roundTrip.run();
            if (histogramNs != null) {
                histogramNs.recordValue(Histograms.clampNs(System.nanoTime() - startNs));
            }
        }
    }

    /**
     * A client and an echo thread over loopback TCP with TCP_NODELAY, 4-byte length frames; the
     * caller writes the request and reads the reply itself, and the echo thread reads and answers
     * (two thread wake-ups per round trip). With hand-offs, the messenger's other two are added:
     * at the echo, the reading thread hands each request to a worker thread that answers it (the
     * reader and the dispatcher); at the client, a reading thread hands each reply to the caller
     * (the reader completing a blocked requester). With a codec, the request is encoded by the
     * caller and decoded by the worker, the reply encoded by the worker and decoded by the caller,
     * each round trip, as the messengers do.
     */
    private static final class RawPingPong implements AutoCloseable {
        private final ServerSocket server;
        private final Socket client;
        private final Socket accepted;
        private final DataOutputStream out;
        private final DataInputStream in;
        private final byte[] requestXml;
        private final byte[] replyXml;
        private final MessageCodec codec;
        private final Message request;
        private final List<Thread> threads = new java.util.concurrent.CopyOnWriteArrayList<>();
        /** Replies handed over by the client's reading thread; null without hand-offs. */
        private java.util.concurrent.BlockingQueue<byte[]> replies;

        /**
         * @param codec   encodes and decodes each request and reply (with {@code request}), or null
         *                for the bytes as they are
         * @param request  the request to encode each time, if {@code codec}
         * @param handOffs whether the messenger's two extra thread hand-offs are added
         */
        RawPingPong(byte[] requestXml, byte[] replyXml, MessageCodec codec, Message request, boolean handOffs)
                throws IOException {
            this.requestXml = requestXml;
            this.replyXml = replyXml;
            this.codec = codec;
            this.request = request;
            server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
            client = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
            client.setTcpNoDelay(true);
            accepted = server.accept();
            accepted.setTcpNoDelay(true);
            out = new DataOutputStream(new BufferedOutputStream(client.getOutputStream()));
            in = new DataInputStream(new BufferedInputStream(client.getInputStream()));
            start(handOffs);
        }

        private void start(boolean handOffs) throws IOException {
            var input = new DataInputStream(new BufferedInputStream(accepted.getInputStream()));
            var output = new DataOutputStream(new BufferedOutputStream(accepted.getOutputStream()));
            if (!handOffs) {
                start("bench-raw-echo", () -> {
                    while (true) {
                        answer(output, readFrame(input));
                    }
                });
                return;
            }
            var requests = new java.util.concurrent.ArrayBlockingQueue<byte[]>(16);
            replies = new java.util.concurrent.ArrayBlockingQueue<>(16);
            start("bench-raw-echo-reader", () -> {
                while (true) {
                    requests.put(readFrame(input));
                }
            });
            start("bench-raw-echo-worker", () -> {
                while (true) {
                    answer(output, requests.take());
                }
            });
            start("bench-raw-client-reader", () -> {
                while (true) {
                    replies.put(readFrame(in));
                }
            });
        }

        private interface Loop {
            void run() throws IOException, InterruptedException;
        }

        private void start(String name, Loop loop) {
            threads.add(Thread.ofPlatform().daemon().name(name).start(() -> {
                try {
                    loop.run();
                } catch (IOException | InterruptedException e) {
                    // Closed or interrupted by close(): the bench is done.
                }
            }));
        }

        private static byte[] readFrame(DataInputStream input) throws IOException {
            byte[] frame = new byte[input.readInt()];
            input.readFully(frame);
            return frame;
        }

        private void answer(DataOutputStream output, byte[] requestFrame) throws IOException {
            byte[] reply = replyXml;
            if (codec != null) {
                Message asked = codec.decode(requestFrame);
                reply = codec.encode(new Message(asked.sender(), asked.profile(), asked.timeStamp(), asked.qos(),
                        asked.contents(), new MessageId("bench-b", 654_321), asked.messageId()));
            }
            output.writeInt(reply.length);
            output.write(reply);
            output.flush();
        }

        void roundTrip() throws IOException, InterruptedException {
            byte[] frame = codec != null ? codec.encode(request) : requestXml;
            out.writeInt(frame.length);
            out.write(frame);
            out.flush();
            byte[] answer = replies != null ? replies.poll(10, TimeUnit.SECONDS) : readFrame(in);
            if (answer == null) {
                throw new IOException("no reply within 10 s: the echo's worker or the client's reader stopped");
            }
            if (codec != null) {
                codec.decode(answer);
            }
        }

        @Override
        public void close() throws IOException {
            client.close();
            accepted.close();
            server.close();
            for (Thread thread : threads) {
                thread.interrupt();
                try {
                    thread.join(1_000);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        }
    }
}
