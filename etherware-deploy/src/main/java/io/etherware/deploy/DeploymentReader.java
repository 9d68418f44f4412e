package io.etherware.deploy;

import io.etherware.core.component.Component;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.deploy.internal.XmlElement;
import io.etherware.deploy.internal.XmlReader;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.SchedulingPolicy;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.CriticalityDeadlinePlacement;
import io.etherware.rt.scheduling.DispatcherSpec;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import java.lang.reflect.Constructor;
import java.lang.reflect.InvocationTargetException;
import java.lang.reflect.Method;
import java.lang.reflect.Modifier;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.function.Supplier;

/**
 * Reads a deployment file ({@code etherware-deployment.xsd}; DEPLOYMENT.md explains it) into a
 * checked {@link Deployment}. The first problem ends the read with a {@link DeploymentException}
 * naming the file, line, element and fix; reading starts nothing, opens no socket or port, and
 * loads component classes without initialising them beyond what their constructors do.
 * Thread-safe.
 */
public final class DeploymentReader {

    private final XmlReader xml = new XmlReader();
    private final ClassLoader classLoader;

    /** A reader that loads component classes through the thread's context class loader. */
    public DeploymentReader() {
        this(Optional.ofNullable(Thread.currentThread().getContextClassLoader())
                .orElse(ClassLoader.getSystemClassLoader()));
    }

    /**
     * A reader that loads component classes through {@code classLoader}.
     *
     * @param classLoader where the components' classes are
     */
    public DeploymentReader(ClassLoader classLoader) {
        this.classLoader = Objects.requireNonNull(classLoader, "classLoader");
    }

    /**
     * Reads {@code file} with no properties.
     *
     * @param file the deployment file
     * @return the checked deployment
     * @throws DeploymentException naming the first problem
     */
    public Deployment read(Path file) throws DeploymentException {
        return read(file, Map.of());
    }

    /**
     * Reads {@code file}, replacing {@code ${name}} and {@code ${name:-default}} in it with
     * {@code properties}.
     *
     * @param file       the deployment file
     * @param properties the launcher's {@code -P name=value}s
     * @return the checked deployment
     * @throws DeploymentException naming the first problem
     */
    public Deployment read(Path file, Map<String, String> properties) throws DeploymentException {
        Objects.requireNonNull(file, "file");
        Objects.requireNonNull(properties, "properties");
        XmlElement root = xml.read(file, properties);
        var at = new Place(file);
        String nodeId = root.attributes().get("id");
        Optional<XmlElement> schedulerElement = root.child("scheduler");
        SchedulerChoice scheduler = scheduler(at, schedulerElement);
        Optional<Deployment.NotifierPlan> notifier = root.child("notifier").isPresent()
                ? Optional.of(notifier(at, root.child("notifier").orElseThrow(), scheduler.rule)) : Optional.empty();
        List<Deployment.ComponentPlan> components = new ArrayList<>();
        var profiles = new HashMap<Profile, XmlElement>();
        for (XmlElement component : root.children("component")) {
            Deployment.ComponentPlan plan = component(at, component);
            XmlElement earlier = profiles.putIfAbsent(plan.profile(), component);
            if (earlier != null) {
                throw at.problem(component, "<component profile=\"" + plan.profile() + "\"> is the profile of the"
                        + " component on line " + earlier.line() + " too; give each component its own profile");
            }
            components.add(plan);
        }
        var sections = new NetworkSections(at, nodeId);
        return new Deployment(file, nodeId, scheduler.plan, notifier, components,
                root.child("network").isPresent() ? Optional.of(sections.network(root.child("network").orElseThrow()))
                        : Optional.empty(),
                root.child("management").isPresent()
                        ? Optional.of(sections.management(root.child("management").orElseThrow()))
                        : Optional.empty(),
                root.child("view").isPresent() ? Optional.of(sections.view(root.child("view").orElseThrow()))
                        : Optional.empty());
    }

    private record SchedulerChoice(Deployment.SchedulerPlan plan, ThreadSchedulingRule rule) {
    }

    private static SchedulerChoice scheduler(Place at, Optional<XmlElement> element) throws DeploymentException {
        if (element.isPresent() && element.get().attribute("type").orElse("realtime").equals("fifo")) {
            XmlElement fifo = element.get();
            for (String realtimeOnly : List.of("realtimeCpus", "lockMemory")) {
                if (fifo.attribute(realtimeOnly).isPresent() && (realtimeOnly.equals("realtimeCpus")
                        || flag(fifo, realtimeOnly, false))) {
                    throw at.problem(fifo, "<scheduler type=\"fifo\"> has " + realtimeOnly + "=\""
                            + fifo.attributes().get(realtimeOnly) + "\", which only type=\"realtime\" uses; remove it");
                }
            }
            if (!fifo.children("dispatcher").isEmpty()) {
                throw at.problem(fifo.children("dispatcher").getFirst(), "<dispatcher> only configures a"
                        + " <scheduler type=\"realtime\">; the fifo scheduler has one ordinary thread");
            }
            return new SchedulerChoice(new Deployment.SchedulerPlan("fifo", () -> new FifoScheduler("fifo-dispatcher"),
                    "fifo (the original Etherware: one ordinary thread)"), null);
        }
        ThreadSchedulingRule rule = ThreadSchedulingRule.tableII();
        RealtimeSchedulerConfig.Builder builder = RealtimeSchedulerConfig.builder().name("rt")
                .placementRule(new CriticalityDeadlinePlacement());
        if (element.isPresent()) {
            XmlElement scheduler = element.get();
            List<XmlElement> dispatchers = scheduler.children("dispatcher");
            if (!dispatchers.isEmpty()) {
                var specs = new ArrayList<DispatcherSpec>();
                for (XmlElement dispatcher : dispatchers) {
                    specs.add(dispatcher(at, dispatcher));
                }
                try {
                    rule = ThreadSchedulingRule.of(specs.toArray(DispatcherSpec[]::new));
                } catch (IllegalArgumentException e) {
                    throw at.problem(scheduler, "<scheduler>'s dispatchers: " + e.getMessage());
                }
            }
            builder.lockMemory(flag(scheduler, "lockMemory", false))
                    .holdCpuLatency(flag(scheduler, "holdCpuLatency", true));
            if (scheduler.attribute("realtimeCpus").isPresent()) {
                builder.realtimeCpus(cpus(at, scheduler, "realtimeCpus"));
            }
        }
        RealtimeSchedulerConfig config;
        try {
            config = builder.threadSchedulingRule(rule).build();
        } catch (IllegalArgumentException e) {
            throw at.problem(element.orElse(null), "<scheduler>: " + e.getMessage());
        }
        String description = "realtime, " + (element.map(e -> e.children("dispatcher").isEmpty()).orElse(true)
                ? "Table II" : "dispatchers") + " " + rule;
        return new SchedulerChoice(new Deployment.SchedulerPlan("realtime", () -> new RealtimeScheduler(config),
                description), rule);
    }

    private static DispatcherSpec dispatcher(Place at, XmlElement dispatcher) throws DeploymentException {
        String policy = dispatcher.attributes().get("policy");
        Optional<String> priority = dispatcher.attribute("priority");
        CpuSet cpus = dispatcher.attribute("cpus").isPresent() ? cpus(at, dispatcher, "cpus") : CpuSet.inherit();
        if (policy.equals("other")) {
            if (priority.isPresent()) {
                throw at.problem(dispatcher, "<dispatcher policy=\"other\" priority=\"" + priority.get() + "\">: an"
                        + " ordinary thread has no real-time priority; remove priority, or use policy=\"fifo\"");
            }
            return DispatcherSpec.nonRealtime().on(cpus);
        }
        int value = priority.map(Integer::parseInt).orElseThrow(() -> at.problem(dispatcher, "<dispatcher policy=\""
                + policy + "\"> needs a priority, " + ThreadSchedulingRule.MIN_REALTIME_PRIORITY + ".."
                + ThreadSchedulingRule.MAX_REALTIME_PRIORITY + " (Table II: 80, 70, 60)"));
        if (value < ThreadSchedulingRule.MIN_REALTIME_PRIORITY || value > ThreadSchedulingRule.MAX_REALTIME_PRIORITY) {
            throw at.problem(dispatcher, "<dispatcher policy=\"" + policy + "\" priority=\"" + value + "\">: the"
                    + " priority must be in " + ThreadSchedulingRule.MIN_REALTIME_PRIORITY + ".."
                    + ThreadSchedulingRule.MAX_REALTIME_PRIORITY + " (Table II: 80, 70, 60)");
        }
        try {
            return new DispatcherSpec(new ThreadPolicy(policy.equals("rr") ? SchedulingPolicy.RR : SchedulingPolicy.FIFO,
                    value), cpus);
        } catch (IllegalArgumentException e) {
            throw at.problem(dispatcher, "<dispatcher>: " + e.getMessage());
        }
    }

    private static Deployment.NotifierPlan notifier(Place at, XmlElement element, ThreadSchedulingRule rule)
            throws DeploymentException {
        NotifierConfig config = rule != null ? NotifierConfig.above(rule) : NotifierConfig.defaults();
        try {
            if (element.attribute("priority").isPresent()) {
                config = config.withThreadPolicy(ThreadPolicy.fifo(Integer.parseInt(element.attributes()
                        .get("priority"))));
            }
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<notifier priority=\"" + element.attributes().get("priority") + "\">: "
                    + e.getMessage());
        }
        if (element.attribute("cpus").isPresent()) {
            config = config.withCpus(cpus(at, element, "cpus"));
        }
        var subscriptions = new ArrayList<Subscription>();
        var names = new HashMap<String, XmlElement>();
        for (XmlElement subscription : element.children("subscription")) {
            String name = subscription.attributes().get("name");
            XmlElement earlier = names.putIfAbsent(name, subscription);
            if (earlier != null) {
                throw at.problem(subscription, "<subscription name=\"" + name + "\"> is given twice (first on line "
                        + earlier.line() + "); give each its own name");
            }
            try {
                subscriptions.add(Subscription.periodic(name, Profile.parse(subscription.attributes().get("target")),
                        Criticality.valueOf(subscription.attribute("criticality").orElse("HIGH")),
                        Durations.parse(subscription.attributes().get("period")).toNanos()));
            } catch (IllegalArgumentException e) {
                throw at.problem(subscription, "<subscription name=\"" + name + "\">: " + e.getMessage());
            }
        }
        return new Deployment.NotifierPlan(config, subscriptions);
    }

    private Deployment.ComponentPlan component(Place at, XmlElement element) throws DeploymentException {
        String className = element.attributes().get("class");
        Profile profile;
        try {
            profile = Profile.parse(element.attributes().get("profile"));
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<component class=\"" + className + "\">: " + e.getMessage());
        }
        String head = "<component profile=\"" + profile + "\" class=\"" + className + "\">: ";
        Class<?> type;
        try {
            type = Class.forName(className, false, classLoader);
        } catch (ClassNotFoundException | LinkageError e) {
            throw at.problem(element, head + "no such class on the class path (" + e + "); check the name and that"
                    + " its jar is on the launcher's class path");
        }
        if (!Modifier.isPublic(type.getModifiers()) || Modifier.isAbstract(type.getModifiers())) {
            throw at.problem(element, head + "the class must be public and not abstract");
        }
        Constructor<?> constructor;
        try {
            constructor = type.getConstructor();
        } catch (NoSuchMethodException e) {
            throw at.problem(element, head + "the class has no public no-argument constructor; add one, or name a"
                    + " ComponentFactory that makes the component");
        }
        var settings = new Settings(at.file, element);
        ComponentFactory factory;
        if (ComponentFactory.class.isAssignableFrom(type)) {
            factory = (ComponentFactory) instantiate(at, element, head, constructor);
        } else if (Component.class.isAssignableFrom(type)) {
            if (!element.children("setting").isEmpty()) {
                throw at.problem(element.children("setting").getFirst(), head + "a Component class takes no settings;"
                        + " name a ComponentFactory that reads them instead");
            }
            factory = new PlainComponent(type, constructor);
        } else {
            throw at.problem(element, head + "the class is neither an io.etherware.deploy.ComponentFactory nor an"
                    + " io.etherware.core.component.Component");
        }
        return new Deployment.ComponentPlan(profile, className, factory, settings, element.line());
    }

    /**
     * A {@code Component} class named directly: made through its no-argument constructor; its
     * contents types registered through its {@code public static registerContents(ContentsTypes)}
     * if it has one (the convention plugin jars follow too).
     */
    private record PlainComponent(Class<?> type, Constructor<?> constructor) implements ComponentFactory {

        @Override
        public void registerContents(ContentsTypes types) {
            Method register;
            try {
                register = type.getMethod("registerContents", ContentsTypes.class);
            } catch (NoSuchMethodException e) {
                return; // it has no types of its own
            }
            if (!Modifier.isStatic(register.getModifiers())) {
                return;
            }
            try {
                register.invoke(null, types);
            } catch (InvocationTargetException e) {
                throw new IllegalStateException(type.getName() + ".registerContents failed: " + e.getCause(),
                        e.getCause());
            } catch (ReflectiveOperationException e) {
                throw new IllegalStateException(type.getName() + ".registerContents cannot be called: " + e, e);
            }
        }

        @Override
        public Supplier<Component> create(Settings settings, Resources resources) {
            return () -> {
                try {
                    return (Component) constructor.newInstance();
                } catch (InvocationTargetException e) {
                    throw new IllegalStateException(type.getName() + "() failed: " + e.getCause(), e.getCause());
                } catch (ReflectiveOperationException e) {
                    throw new IllegalStateException(type.getName() + "() cannot be called: " + e, e);
                }
            };
        }
    }

    private static Object instantiate(Place at, XmlElement element, String head, Constructor<?> constructor)
            throws DeploymentException {
        try {
            return constructor.newInstance();
        } catch (InvocationTargetException e) {
            throw at.problem(element, head + "its constructor failed: " + e.getCause());
        } catch (ReflectiveOperationException | LinkageError e) {
            throw at.problem(element, head + "cannot be made: " + e);
        }
    }

    /**
     * An {@code xs:boolean} attribute: {@code true} or {@code 1} is true, {@code false} or
     * {@code 0} false (the schema allows nothing else).
     */
    static boolean flag(XmlElement element, String attribute, boolean defaultValue) {
        return element.attribute(attribute).map(String::strip).map(v -> v.equals("true") || v.equals("1"))
                .orElse(defaultValue);
    }

    static CpuSet cpus(Place at, XmlElement element, String attribute) throws DeploymentException {
        try {
            return CpuSet.parse(element.attributes().get(attribute));
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<" + element.name() + ">: " + e.getMessage());
        }
    }

    /** Where problems are: the file, and an element's line. */
    record Place(Path file) {

        DeploymentException problem(XmlElement element, String message) {
            return element == null ? new DeploymentException(file, 0, 0, message, null)
                    : new DeploymentException(file, element.line(), element.column(), message, null);
        }
    }
}
