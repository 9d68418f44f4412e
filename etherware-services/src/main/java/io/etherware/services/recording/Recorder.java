package io.etherware.services.recording;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.MessageTap;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.io.BufferedOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.util.Collection;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.LongAdder;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Records the messages a node is asked to deliver to chosen profiles, with their QoS and time
 * stamps, to a file ({@code etherware-services/RECORDING.md} gives the format); read it back with
 * {@link Recording}. A message is recorded if its profile, as its sender addressed it, matches one
 * of the chosen profiles as a query ({@link Profile#matches}): {@code controller} records every
 * controller's messages, {@code controller[pendulum=1]} that one's. Messages made on the node,
 * arrived from the network and replies alike.
 *
 * <p>Real time: the node's sending threads only offer the message to a bounded queue; a thread of
 * the recorder's own, at ordinary priority, encodes (XML, the node's {@link MessageCodec}) and
 * writes. If the queue is full the message is not recorded and {@link #dropped()} counts it: a
 * recorder never slows the node down. A message whose contents type the node's registry cannot
 * encode (a local-only type) is skipped and counted in {@link #unencodable()}.
 *
 * <p>Thread-safety: any thread; {@link #close} is idempotent.
 */
public final class Recorder implements AutoCloseable {

    private static final Logger log = LoggerFactory.getLogger(Recorder.class);
    /** Messages waiting to be written, by default. */
    public static final int DEFAULT_CAPACITY = 65_536;

    private record Entry(long atNs, Message message) {
    }

    private static final Entry END = new Entry(0, null);

    private final EtherwareNode node;
    private final Path file;
    private final List<Profile> profiles;
    private final BlockingQueue<Entry> queue;
    private final MessageCodec codec;
    private final DataOutputStream out;
    private final long startNs;
    private final MessageTap.Registration registration;
    private final Thread writer;
    private final LongAdder recorded = new LongAdder();
    private final LongAdder dropped = new LongAdder();
    private final LongAdder unencodable = new LongAdder();
    private volatile IOException failure;
    private final AtomicBoolean closed = new AtomicBoolean();

    private Recorder(EtherwareNode node, Path file, List<Profile> profiles, int capacity) throws IOException {
        this.node = node;
        this.file = file;
        this.profiles = profiles;
        this.queue = new ArrayBlockingQueue<>(capacity);
        this.codec = new MessageCodec(node.contentsTypes());
        this.out = new DataOutputStream(new BufferedOutputStream(Files.newOutputStream(file,
                StandardOpenOption.CREATE, StandardOpenOption.TRUNCATE_EXISTING, StandardOpenOption.WRITE)));
        this.startNs = node.clock().nanoTime();
        RecordingFormat.writeHeader(out, node.nodeId(), node.clock().epochNanos());
        this.writer = Thread.ofPlatform().daemon().name("etherware-recorder-" + node.nodeId()).start(this::write);
        this.registration = node.tap(this::seen);
    }

    /**
     * Starts recording, with room for {@link #DEFAULT_CAPACITY} messages waiting to be written.
     *
     * @param node     the node whose messages to record
     * @param file     the file to write; replaced if it exists
     * @param profiles the profiles (queries) whose messages to record; at least one
     * @return the running recorder; close it to finish the file
     * @throws IOException              if the file cannot be written
     * @throws IllegalArgumentException if {@code profiles} is empty
     */
    public static Recorder start(EtherwareNode node, Path file, Collection<Profile> profiles) throws IOException {
        return start(node, file, profiles, DEFAULT_CAPACITY);
    }

    /**
     * Starts recording.
     *
     * @param node     the node whose messages to record
     * @param file     the file to write; replaced if it exists
     * @param profiles the profiles (queries) whose messages to record; at least one
     * @param capacity how many messages may wait to be written; beyond that they are dropped
     * @return the running recorder; close it to finish the file
     * @throws IOException              if the file cannot be written
     * @throws IllegalArgumentException if {@code profiles} is empty or {@code capacity} &lt; 1
     */
    public static Recorder start(EtherwareNode node, Path file, Collection<Profile> profiles, int capacity)
            throws IOException {
        Objects.requireNonNull(node, "node");
        Objects.requireNonNull(file, "file");
        List<Profile> chosen = List.copyOf(profiles);
        if (chosen.isEmpty()) {
            throw new IllegalArgumentException("profiles is empty: name at least one profile (a query, e.g."
                    + " Profile.parse(\"controller\")) whose messages to record");
        }
        if (capacity < 1) {
            throw new IllegalArgumentException("capacity=" + capacity + " must be >= 1");
        }
        return new Recorder(node, file, chosen, capacity);
    }

    /** Sending thread: offers a chosen message to the queue, never blocking. */
    private void seen(Message message) {
        for (Profile query : profiles) {
            if (message.profile().matches(query)) {
                if (!queue.offer(new Entry(node.clock().nanoTime() - startNs, message))) {
                    dropped.increment();
                }
                return;
            }
        }
    }

    /** The recorder's thread: encodes and writes until {@link #close}. */
    private void write() {
        try {
            while (true) {
                Entry entry = queue.take();
                if (entry == END) {
                    return;
                }
                byte[] document;
                try {
                    document = codec.encode(entry.message());
                } catch (RuntimeException e) {
                    if (unencodable.sum() == 0) {
                        log.warn("recorder of node {}: message {} to '{}' is not recorded: {} (logged once)",
                                node.nodeId(), entry.message().messageId(), entry.message().profile(), e.getMessage());
                    }
                    unencodable.increment();
                    continue;
                }
                RecordingFormat.writeRecord(out, entry.atNs(), document);
                recorded.increment();
            }
        } catch (IOException e) {
            failure = e;
            log.error("recorder of node {}: writing {} failed; recording stopped", node.nodeId(), file, e);
            registration.close();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /** {@return the messages written so far} */
    public long recorded() {
        return recorded.sum();
    }

    /** {@return the messages not recorded because the queue was full} */
    public long dropped() {
        return dropped.sum();
    }

    /** {@return the messages not recorded because their contents could not be encoded} */
    public long unencodable() {
        return unencodable.sum();
    }

    /** {@return the file being written} */
    public Path file() {
        return file;
    }

    /**
     * Stops recording: no message sent after this begins is recorded; the ones already taken
     * are written, then the file is closed.
     *
     * @throws UncheckedIOException if writing or closing the file failed
     */
    @Override
    public void close() {
        if (!closed.compareAndSet(false, true)) {
            return;
        }
        registration.close();
        try {
            while (writer.isAlive() && !queue.offer(END, 100, TimeUnit.MILLISECONDS)) {
                // the writer is catching up with a full queue
            }
            writer.join(TimeUnit.SECONDS.toMillis(30));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        try {
            out.close();
        } catch (IOException e) {
            throw new UncheckedIOException("closing the recording " + file + " failed", e);
        }
        IOException failed = failure;
        if (failed != null) {
            throw new UncheckedIOException("writing the recording " + file + " failed", failed);
        }
    }
}
