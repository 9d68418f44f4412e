package io.etherware.examples.bench;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import java.io.IOException;
import java.lang.management.GarbageCollectorMXBean;
import java.lang.management.ManagementFactory;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.atomic.AtomicReference;

/**
 * The machine and JVM a report was measured on: cores, kernel, JDK, the JVM's options and
 * collectors, the load average, and whether SCHED_FIFO is granted here, as the OS reports it back
 * for a thread that asked for it. Immutable.
 *
 * @param cores            available processors
 * @param kernel           the kernel release ({@code os.name os.version})
 * @param jdk              {@code java.vm.name} and the runtime version
 * @param jvmOptions       {@code RuntimeMXBean.getInputArguments()}
 * @param collectors       the garbage collectors' MXBean names
 * @param loadAverage      {@code /proc/loadavg} at the start of the run, or {@code unknown}
 * @param sched            the probe thread's policy as read back from the OS, e.g. {@code SCHED_FIFO/81}
 * @param schedFifoGranted whether the OS granted SCHED_FIFO to the probe thread
 * @param schedNote        the platform's reason when it is not available, else empty
 */
public record MachineInfo(int cores, String kernel, String jdk, List<String> jvmOptions, List<String> collectors,
                          String loadAverage, String sched, boolean schedFifoGranted, String schedNote) {

    /** Reads the machine now; briefly runs one probe thread that asks for SCHED_FIFO {@code priority}. */
    public static MachineInfo probe(int priority) {
        var grant = new AtomicReference<ThreadGrant>();
        var readBack = new AtomicReference<ThreadPolicy>(ThreadPolicy.NON_REALTIME);
        Thread probe = Thread.ofPlatform().name("bench-sched-probe").start(() -> {
            Platform platform = Platform.current();
            grant.set(platform.configureCurrentThreadWithoutWarning(ThreadPolicy.fifo(priority), CpuSet.inherit()));
            readBack.set(platform.currentThreadPolicy()); // what the OS says, not what was asked
        });
        try {
            probe.join();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        ThreadPolicy policy = readBack.get();
        String note = Platform.current().unavailableReason().orElse(
                grant.get() != null && !grant.get().isPolicyGranted() ? grant.get().toLine() : "");
        return new MachineInfo(Runtime.getRuntime().availableProcessors(),
                System.getProperty("os.name") + " " + System.getProperty("os.version"),
                System.getProperty("java.vm.name") + " " + Runtime.version(),
                List.copyOf(ManagementFactory.getRuntimeMXBean().getInputArguments()),
                ManagementFactory.getGarbageCollectorMXBeans().stream().map(GarbageCollectorMXBean::getName).toList(),
                readLoadAverage(), policy.toString(), policy.isRealtime(), note);
    }

    /** {@code /proc/loadavg}, trimmed, or {@code unknown}. */
    static String readLoadAverage() {
        try {
            return Files.readString(Path.of("/proc/loadavg")).trim();
        } catch (IOException e) {
            return "unknown";
        }
    }
}
